#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_EXT_nonuniform_qualifier : require

struct _50
{
    uint _m0;
    uint _m1;
    uint _m2;
    uint _m3;
};

struct _51
{
    vec4 _m0;
    vec4 _m1;
    vec4 _m2;
};

struct _52
{
    uint _m0;
    uint _m1;
    float _m2;
    float _m3;
    vec4 _m4;
    vec4 _m5;
    uvec4 _m6;
    vec4 _m7;
    vec4 _m8;
    vec4 _m9;
};

struct _56
{
    vec4 _m0;
    vec4 _m1;
    vec4 _m2;
    vec4 _m3;
    uvec4 _m4;
};

layout(set = 0, binding = 3, std430) readonly buffer _84_14
{
    _50 _m0[];
} _14;

layout(set = 0, binding = 4, std430) readonly buffer _86_15
{
    _51 _m0[];
} _15;

layout(set = 0, binding = 5, std430) readonly buffer _88_16
{
    _52 _m0[];
} _16;

layout(location = 0) rayPayloadInEXT _56 _19;
hitAttributeEXT vec3 _17;

void main()
{
    uint _680 = uint(gl_InstanceCustomIndexEXT) + uint(gl_PrimitiveID);
    vec3 _2424 = gl_ObjectRayOriginEXT + vec3(gl_ObjectRayDirectionEXT.x * gl_RayTmaxEXT, gl_ObjectRayDirectionEXT.y * gl_RayTmaxEXT, gl_ObjectRayDirectionEXT.z * gl_RayTmaxEXT);
    vec3 _1696;
    if (_16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m0 == 2u)
    {
        float _1638 = 1.0 / sqrt(fma(_17.z, _17.z, fma(_17.x, _17.x, _17.y * _17.y)));
        float _1645 = 0.001000000047497451305389404296875 / _16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m5.w;
        float _1662 = (floor(fma(-(_17.x * _1638), _1645, _2424.x) * _16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m5.w) + floor(fma(-(_17.y * _1638), _1645, _2424.y) * _16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m5.w)) + floor(fma(-(_17.z * _1638), _1645, _2424.z) * _16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m5.w);
        vec3 _1689;
        if ((((_1662 == _1662) ? ((_1662 > 2147483520.0) ? 2147483647 : ((!(_1662 >= (-2147483648.0))) ? int(0x80000000) : int(_1662))) : 0) & 1) == 0)
        {
            _1689 = vec3(_16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m4.xyz);
        }
        else
        {
            _1689 = vec3(_16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m5.xyz);
        }
        _1696 = _1689;
    }
    else
    {
        _1696 = vec3(_16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m4.xyz);
    }
    float _2474 = fma(gl_WorldToObjectEXT[0].z, _17.z, fma(gl_WorldToObjectEXT[0].x, _17.x, gl_WorldToObjectEXT[0].y * _17.y));
    float _2475 = fma(gl_WorldToObjectEXT[1].z, _17.z, fma(gl_WorldToObjectEXT[1].x, _17.x, gl_WorldToObjectEXT[1].y * _17.y));
    float _2476 = fma(gl_WorldToObjectEXT[2].z, _17.z, fma(gl_WorldToObjectEXT[2].x, _17.x, gl_WorldToObjectEXT[2].y * _17.y));
    float _2483 = 1.0 / sqrt(fma(_2476, _2476, fma(_2474, _2474, _2475 * _2475)));
    float _2484 = _2474 * _2483;
    float _2485 = _2475 * _2483;
    float _2486 = _2476 * _2483;
    vec3 _2487 = vec3(_2484, _2485, _2486);
    vec3 _2506;
    if (fma(_2486, gl_WorldRayDirectionEXT.z, fma(_2484, gl_WorldRayDirectionEXT.x, _2485 * gl_WorldRayDirectionEXT.y)) > 0.0)
    {
        _2506 = -_2487;
    }
    else
    {
        _2506 = _2487;
    }
    float _2533 = fma(gl_WorldToObjectEXT[0].z, _17.z, fma(gl_WorldToObjectEXT[0].x, _17.x, gl_WorldToObjectEXT[0].y * _17.y));
    float _2534 = fma(gl_WorldToObjectEXT[1].z, _17.z, fma(gl_WorldToObjectEXT[1].x, _17.x, gl_WorldToObjectEXT[1].y * _17.y));
    float _2535 = fma(gl_WorldToObjectEXT[2].z, _17.z, fma(gl_WorldToObjectEXT[2].x, _17.x, gl_WorldToObjectEXT[2].y * _17.y));
    float _2542 = 1.0 / sqrt(fma(_2535, _2535, fma(_2533, _2533, _2534 * _2534)));
    float _2543 = _2533 * _2542;
    float _2544 = _2534 * _2542;
    float _2545 = _2535 * _2542;
    vec3 _2546 = vec3(_2543, _2544, _2545);
    vec3 _2446;
    if (fma(_2545, _2506.z, fma(_2543, _2506.x, _2544 * _2506.y)) < 0.0)
    {
        _2446 = -_2546;
    }
    else
    {
        _2446 = _2546;
    }
    _19._m0 = vec4(fma(gl_WorldRayDirectionEXT.x, gl_RayTmaxEXT, gl_WorldRayOriginEXT.x), fma(gl_WorldRayDirectionEXT.y, gl_RayTmaxEXT, gl_WorldRayOriginEXT.y), fma(gl_WorldRayDirectionEXT.z, gl_RayTmaxEXT, gl_WorldRayOriginEXT.z), gl_RayTmaxEXT);
    _19._m1 = vec4(_2446, 0.0);
    _19._m2 = vec4(_2506, 0.0);
    _19._m3 = vec4(_1696.x * _15._m0[_680]._m2.x, _1696.y * _15._m0[_680]._m2.y, _1696.z * _15._m0[_680]._m2.z, 0.0);
    _19._m4 = uvec4(uint(gl_InstanceID), uint(gl_PrimitiveID), _16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m0, gl_HitKindEXT);
}

