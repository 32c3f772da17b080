#version 460
// Twin of twinray_stages::explain_query: rays traced inline by ray queries.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#define SHADOW_QUERY
#define RENDER_COMPUTE
#include "twinray_layout.glsl"
#include "explain_main.glsl"
