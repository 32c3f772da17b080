//! One scene at several instance counts: the first `[[grids]]` of the scene's text is resized
//! to about N objects over the same area (the same extent, centre and look), so the image
//! stays comparable while the TLAS grows.

use twinray_host::error::{Error, Result};

/// The scene text with its first grid holding about `instances` objects: n x n on the grid's
/// two longest axes, n the nearest whole square root, spacing and object scale shrunk or
/// grown so that the grid covers the same area. The count actually used is the scene's.
pub fn resize_grid(text: &str, instances: usize) -> Result<String> {
    let fail = |m: String| Error::Input(format!("resizing the scene's grid to {instances} instances: {m}"));
    let mut doc: toml::Table = text.parse().map_err(|e: toml::de::Error| fail(e.message().to_string()))?;
    let grid = doc
        .get_mut("grids")
        .and_then(|g| g.as_array_mut())
        .and_then(|g| g.first_mut())
        .and_then(|g| g.as_table_mut())
        .ok_or_else(|| fail("the scene has no [[grids]]".into()))?;
    let floats = |grid: &toml::Table, key: &str, default: [f64; 3]| -> Result<[f64; 3]> {
        match grid.get(key) {
            None => Ok(default),
            Some(v) => {
                let items = v.as_array().ok_or_else(|| fail(format!("grids[0].{key} is not an array")))?;
                let numbers: Vec<f64> =
                    items.iter().filter_map(|x| x.as_float().or(x.as_integer().map(|i| i as f64))).collect();
                numbers.try_into().map_err(|_| fail(format!("grids[0].{key} is not three numbers")))
            }
        }
    };
    let count = floats(grid, "count", [1.0; 3])?;
    let spacing = floats(grid, "spacing", [0.0; 3])?;
    let origin = floats(grid, "origin", [0.0; 3])?;
    // The two axes with the most objects carry the n x n; the third keeps its count.
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| count[b].total_cmp(&count[a]));
    let n = (instances.max(1) as f64).sqrt().round().max(1.0);
    let mut new_count = count;
    let mut new_spacing = spacing;
    let mut new_origin = origin;
    let mut shrink = 1.0;
    for &axis in &axes[..2] {
        let centre = origin[axis] + spacing[axis] * (count[axis] - 1.0) / 2.0;
        new_count[axis] = n;
        new_spacing[axis] = spacing[axis] * count[axis] / n;
        new_origin[axis] = centre - new_spacing[axis] * (n - 1.0) / 2.0;
        shrink = count[axis] / n;
    }
    let array = |v: [f64; 3]| toml::Value::Array(v.iter().map(|&x| toml::Value::Float(x)).collect());
    let counts = toml::Value::Array(new_count.iter().map(|&c| toml::Value::Integer(c as i64)).collect());
    grid.insert("count".into(), counts);
    grid.insert("spacing".into(), array(new_spacing));
    grid.insert("origin".into(), array(new_origin));
    let scale = match grid.get("scale") {
        None => toml::Value::Float(shrink),
        Some(toml::Value::Float(s)) => toml::Value::Float(s * shrink),
        Some(toml::Value::Integer(s)) => toml::Value::Float(*s as f64 * shrink),
        Some(_) => array(floats(grid, "scale", [1.0; 3])?.map(|s| s * shrink)),
    };
    grid.insert("scale".into(), scale);
    toml::to_string(&doc).map_err(|e| fail(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use twinray_host::scene::{MeshFiles, Scene};

    #[test]
    fn the_swarm_resizes_over_the_same_area() {
        let text = twinray_host::scene::BUILTIN.iter().find(|(n, _)| *n == "swarm").unwrap().1;
        for (asked, got) in [(1000, 1024), (10_000, 10_000), (100_000, 99_856)] {
            let resized = resize_grid(text, asked).unwrap();
            let scene = Scene::parse(&resized, "swarm", MeshFiles::Builtin).unwrap();
            assert_eq!(scene.file.objects.len(), got);
            let xs: Vec<f32> = scene.animation.as_ref().unwrap().rest.objects.iter().map(|o| o.translate[0]).collect();
            let (lo, hi) = xs.iter().fold((f32::MAX, f32::MIN), |(l, h), &x| (l.min(x), h.max(x)));
            let spacing = 80.0 / (got as f32).sqrt();
            assert!((lo + 40.0 - spacing / 2.0).abs() < 1e-3 && (hi - 40.0 + spacing / 2.0).abs() < 1e-3, "{lo} {hi}");
        }
        assert!(resize_grid("name = \"x\"", 10).is_err());
    }
}
