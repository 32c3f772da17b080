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
    vec3 _wn = normalize(_17 * mat3(gl_WorldToObjectEXT[0], gl_WorldToObjectEXT[1], gl_WorldToObjectEXT[2]));
    vec3 _2506 = dot(_wn, gl_WorldRayDirectionEXT) > 0.0 ? -_wn : _wn;
    vec3 _2446 = dot(_wn, _2506) < 0.0 ? -_wn : _wn;
    _19._m0 = vec4(fma(gl_WorldRayDirectionEXT.x, gl_RayTmaxEXT, gl_WorldRayOriginEXT.x), fma(gl_WorldRayDirectionEXT.y, gl_RayTmaxEXT, gl_WorldRayOriginEXT.y), fma(gl_WorldRayDirectionEXT.z, gl_RayTmaxEXT, gl_WorldRayOriginEXT.z), gl_RayTmaxEXT);
    _19._m1 = vec4(_2446, 0.0);
    _19._m2 = vec4(_2506, 0.0);
    _19._m3 = vec4(_1696.x * _15._m0[_680]._m2.x, _1696.y * _15._m0[_680]._m2.y, _1696.z * _15._m0[_680]._m2.z, 0.0);
    _19._m4 = uvec4(uint(gl_InstanceID), uint(gl_PrimitiveID), _16._m0[_14._m0[uint(gl_InstanceID)]._m0]._m0, gl_HitKindEXT);
}

