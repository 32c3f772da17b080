//! `twinray info`: the device twinray would use, its driver and ray tracing properties.

use crate::args::GlobalArgs;
use crate::session::context;
use anyhow::Result;
use std::process::ExitCode;

pub fn info(global: &GlobalArgs, json: bool) -> Result<ExitCode> {
    let ctx = context(global)?;
    let i = &ctx.info;
    let cache = ctx.pipeline_cache_state();
    if json {
        let mut value = serde_json::to_value(i)?;
        value["pipeline_cache"] = serde_json::json!(cache.map(|(file, bytes)| serde_json::json!({
            "file": file,
            "loaded_bytes": bytes,
        })));
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        println!("device      {} ({})", i.name, i.device_type);
        println!("driver      {} {}", i.driver_name, i.driver_info);
        println!("vulkan      {}", i.api_version);
        println!(
            "sbt         handle size {}, handle alignment {}, base alignment {}",
            i.shader_group_handle_size, i.shader_group_handle_alignment, i.shader_group_base_alignment
        );
        println!("recursion   max depth {}", i.max_ray_recursion_depth);
        println!(
            "dispatch    max {} invocations, image side {}",
            i.max_ray_dispatch_invocation_count, i.max_image_dimension_2d
        );
        let timing = if i.timestamp_valid_bits > 0 {
            format!("{} ns per tick, {} valid bits", i.timestamp_period_ns, i.timestamp_valid_bits)
        } else {
            "not available on this queue".into()
        };
        println!("timestamps  {timing}");
        println!(
            "libraries   VK_KHR_pipeline_library {}; pipelines made {:?}",
            if i.pipeline_library { "yes" } else { "no" },
            ctx.pipeline_kind()
        );
        let stages: Vec<&str> = twinray_host::sets::Stage::ALL.iter().map(|s| s.name()).collect();
        println!("stages      {} (compute: the ray query renderer)", stages.join(", "));
        println!(
            "ray query   VK_KHR_ray_query {}",
            if i.ray_query {
                "yes: shadow_method = \"query\" and renderer = \"compute\" scenes render"
            } else {
                "no: shadow_method = \"query\" and renderer = \"compute\" scenes are refused"
            }
        );
        let r = i.robustness;
        let on = |b: bool| if b { "on" } else { "off" };
        println!(
            "robustness  VK_EXT_robustness2: robustBufferAccess2 {}, robustImageAccess2 {}{}",
            on(r.buffer_access2),
            on(r.image_access2),
            if r.buffer_access2 {
                " (a stage reading outside a buffer reads zeros, the same on every driver)"
            } else if global.no_robust_access {
                " (--no-robust-access)"
            } else {
                " (the device lacks it: a stray read gives what the driver gives)"
            }
        );
        println!(
            "host AS     accelerationStructureHostCommands {} (twinray builds acceleration structures on the device)",
            if i.host_acceleration_structure_commands { "yes" } else { "no" }
        );
        match ctx.pipeline_threads() {
            0 => println!("deferred    no: pipelines created directly (under the validation layer)"),
            n => println!("deferred    pipeline creation joined by {n} threads"),
        }
        match cache {
            Some((file, 0)) => println!("pipelines   cache {} (cold: nothing read)", file.display()),
            Some((file, bytes)) => println!("pipelines   cache {} ({bytes} bytes read)", file.display()),
            None => println!("pipelines   no cache (--no-pipeline-cache)"),
        }
        if let Some(threads) = i.cpu_threads {
            println!("threads     {threads} (a CPU device: LP_NUM_THREADS, else the CPU count)");
        }
    }
    Ok(ExitCode::SUCCESS)
}
