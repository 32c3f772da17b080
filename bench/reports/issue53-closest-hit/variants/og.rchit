#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_EXT_nonuniform_qualifier : require

struct Material
{
    uint kind;
    uint cutout_pattern;
    float cutout_scale;
    float cutout_threshold;
    vec4 color_a;
    vec4 color_b;
    uvec4 _texture;
    vec4 uv_u;
    vec4 uv_v;
    vec4 emission;
};

struct Primitive
{
    vec4 a;
    vec4 b;
    vec4 tint;
};

struct HitPayload
{
    vec4 position;
    vec4 shading_normal;
    vec4 geometric_normal;
    vec4 color;
    uvec4 ids;
};

struct ObjectData
{
    uint material;
    uint vertex_base;
    uint index_base;
    uint shape;
};

layout(set = 0, binding = 5, std430) readonly buffer Materials
{
    Material materials[];
} _1305;

layout(set = 0, binding = 3, std430) readonly buffer Objects
{
    ObjectData objects[];
} _1310;

layout(set = 0, binding = 4, std430) readonly buffer Primitives
{
    Primitive primitives[];
} _1329;

layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec3 normal;

void main()
{
    uint _1413 = uint(gl_InstanceID);
    uint _1419 = uint(gl_InstanceCustomIndexEXT + gl_PrimitiveID);
    Material _1531;
    _1531.kind = _1305.materials[_1310.objects[_1413].material].kind;
    _1531.cutout_pattern = _1305.materials[_1310.objects[_1413].material].cutout_pattern;
    _1531.cutout_scale = _1305.materials[_1310.objects[_1413].material].cutout_scale;
    _1531.cutout_threshold = _1305.materials[_1310.objects[_1413].material].cutout_threshold;
    _1531.color_a = _1305.materials[_1310.objects[_1413].material].color_a;
    _1531.color_b = _1305.materials[_1310.objects[_1413].material].color_b;
    _1531._texture = _1305.materials[_1310.objects[_1413].material]._texture;
    _1531.uv_u = _1305.materials[_1310.objects[_1413].material].uv_u;
    _1531.uv_v = _1305.materials[_1310.objects[_1413].material].uv_v;
    _1531.emission = _1305.materials[_1310.objects[_1413].material].emission;
    Primitive _1544;
    _1544.a = _1329.primitives[_1419].a;
    _1544.b = _1329.primitives[_1419].b;
    _1544.tint = _1329.primitives[_1419].tint;
    vec3 _3578;
    do
    {
        if (_1531.kind == 2u)
        {
            vec3 _2816 = floor(((gl_ObjectRayOriginEXT + (gl_ObjectRayDirectionEXT * gl_RayTmaxEXT)) - (normalize(normal) * (0.001000000047497451305389404296875 / _1531.color_b.w))) * _1531.color_b.w);
            vec3 _3577;
            if ((int((_2816.x + _2816.y) + _2816.z) & 1) == 0)
            {
                _3577 = _1531.color_a.xyz;
            }
            else
            {
                _3577 = _1531.color_b.xyz;
            }
            _3578 = _3577;
            break;
        }
        _3578 = _1531.color_a.xyz;
        break;
    } while(false);
    vec3 _2877 = normalize(normal * mat3(gl_WorldToObjectEXT[0], gl_WorldToObjectEXT[1], gl_WorldToObjectEXT[2]));
    vec3 _3623;
    if (dot(_2877, gl_WorldRayDirectionEXT) > 0.0)
    {
        _3623 = -_2877;
    }
    else
    {
        _3623 = _2877;
    }
    vec3 _3626;
    if (dot(_2877, _3623) < 0.0)
    {
        _3626 = -_2877;
    }
    else
    {
        _3626 = _2877;
    }
    payload.position = vec4(gl_WorldRayOriginEXT + (gl_WorldRayDirectionEXT * gl_RayTmaxEXT), gl_RayTmaxEXT);
    payload.shading_normal = vec4(_3626, 0.0);
    payload.geometric_normal = vec4(_3623, 0.0);
    payload.color = vec4(_3578 * _1544.tint.xyz, 0.0);
    payload.ids = uvec4(_1413, uint(gl_PrimitiveID), _1531.kind, gl_HitKindEXT);
}

