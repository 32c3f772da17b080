#version 460
// Twin of twinray_stages::render_compute: the compute renderer (renderer = "compute"), which
// traces primary and shadow rays inline with ray queries, with no pipeline stages or SBT.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#define SHADOW_QUERY
#define RENDER_COMPUTE
#include "twinray_layout.glsl"

// RENDER_GROUP_SIZE x RENDER_GROUP_SIZE pixels per workgroup.
layout(local_size_x = RENDER_GROUP_SIZE, local_size_y = RENDER_GROUP_SIZE) in;

#include "raygen_main.glsl"
