//! `twinray scenes`: the built-in scenes, and every kind a scene file can use.

use anyhow::Result;
use std::process::ExitCode;
use twinray_host::Scene;

pub fn scenes(json: bool) -> Result<ExitCode> {
    let mut rows = Vec::new();
    for (name, _) in twinray_host::scene::BUILTIN {
        let scene = Scene::load(Some(name))?;
        let data = scene.build();
        let groups: Vec<_> = data.plan.hit_groups.iter().map(|g| g.name()).collect();
        rows.push(serde_json::json!({
            "name": name,
            "description": scene.file.description,
            "width": scene.file.image.width,
            "height": scene.file.image.height,
            "samples": scene.file.image.samples,
            "objects": scene.file.objects.len(),
            "lights": scene.file.lights.len(),
            "frames": scene.frame_count(),
            "hit_groups": groups,
            "shadows": data.plan.shadows,
            "features": twinray_shared::features::names(data.plan.features),
        }));
    }
    let kinds = twinray_host::scene::file::kinds();
    if json {
        let kinds: serde_json::Map<_, _> =
            kinds.iter().map(|(what, list)| (what.to_string(), serde_json::json!(list))).collect();
        println!("{}", serde_json::json!({ "scenes": rows, "kinds": kinds }));
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{:<10} {:>9} {:>7} {:>6} {:>7}  {:<22} {:<28} description",
        "scene", "size", "objects", "frames", "shadows", "features", "hit groups"
    );
    for r in &rows {
        println!(
            "{:<10} {:>9} {:>7} {:>6} {:>7}  {:<22} {:<28} {}",
            r["name"].as_str().unwrap_or_default(),
            format!("{}x{}", r["width"], r["height"]),
            r["objects"].as_u64().unwrap_or(0),
            r["frames"].as_u64().unwrap_or(1),
            if r["shadows"] == true { "yes" } else { "no" },
            r["features"].as_str().unwrap_or_default(),
            r["hit_groups"]
                .as_array()
                .map(|g| g.iter().filter_map(|v| v.as_str()).collect::<Vec<_>>().join(","))
                .unwrap_or_default(),
            r["description"].as_str().unwrap_or_default(),
        );
    }
    println!();
    for (what, list) in kinds {
        println!("{what:<10} {}", list.join(", "));
    }
    println!("\nEvery field of a scene file: docs/scene-format.md");
    Ok(ExitCode::SUCCESS)
}
