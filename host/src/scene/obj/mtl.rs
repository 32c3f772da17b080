//! Material libraries (MTL), read here rather than by tobj, whose reader refuses files other
//! tools write and read (two spaces between values, a material without a name): each
//! statement twinray uses is read on its own, and one it cannot read is skipped.

use std::collections::HashMap;

/// The materials of an MTL file's `text`, and their indices by name, as tobj's loader hands
/// them on.
pub fn parse(text: &str) -> (Vec<tobj::Material>, HashMap<String, usize>) {
    let mut materials: Vec<tobj::Material> = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        let Some(key) = line.split_whitespace().next().filter(|k| !k.starts_with('#')) else { continue };
        let rest = line[key.len()..].trim();
        if key == "newmtl" {
            materials.push(tobj::Material { name: rest.to_string(), ..Default::default() });
            continue;
        }
        let Some(m) = materials.last_mut() else { continue };
        match key {
            "Kd" => m.diffuse = color(rest),
            "Ke" => m.emissive = color(rest),
            "Ks" => m.specular = color(rest),
            "d" => m.dissolve = rest.parse().ok(),
            "Tr" => m.dissolve = rest.parse::<f32>().ok().map(|t| 1.0 - t),
            "map_Kd" => m.diffuse_texture = Some(map_file(rest)),
            "map_Ks" => m.specular_texture = Some(map_file(rest)),
            "map_Ka" => m.ambient_texture = Some(map_file(rest)),
            "map_Ns" => m.shininess_texture = Some(map_file(rest)),
            "map_d" => m.dissolve_texture = Some(map_file(rest)),
            "map_Bump" | "map_bump" | "bump" | "norm" => m.normal_texture = Some(map_file(rest)),
            "map_Ke" => drop(m.unknown_param.insert(key.into(), map_file(rest))),
            _ => {}
        }
    }
    let names = materials.iter().enumerate().map(|(i, m)| (m.name.clone(), i)).collect();
    (materials, names)
}

/// An RGB colour statement's value: three numbers, or one for a grey; `None` for anything
/// else, or a value that is negative or not finite.
fn color(rest: &str) -> Option<[f32; 3]> {
    let values: Vec<f32> = rest.split_whitespace().map(str::parse).collect::<Result<_, _>>().ok()?;
    let rgb = match values[..] {
        [v] => [v; 3],
        [r, g, b] => [r, g, b],
        _ => return None,
    };
    rgb.iter().all(|v| v.is_finite() && *v >= 0.0).then_some(rgb)
}

/// The file of a texture statement: its last word after options (`-s 2 2 1 wood.png`), else
/// all of it (a name with spaces).
fn map_file(rest: &str) -> String {
    match rest.starts_with('-') {
        true => rest.split_whitespace().last().unwrap_or_default().to_string(),
        false => rest.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statements_other_tools_write_are_read() {
        let text = "# a comment\nKd 1 0 0\nnewmtl Base\nKa  0.2 0.2 0.2\nKd  0.2 0.3 0.4\nd  0.5\n\
                    map_Kd -s 2 2 1 .\\wood.jpg\nnewmtl \nKd 0.5\nKe 1 nan 0\nnewmtl with spaces \n\
                    map_Kd my texture.png\nmap_Ke glow.png\nTr 0.25\nKd -1 0 0\n";
        let (m, names) = parse(text);
        assert_eq!(m.len(), 3, "a statement before newmtl belongs to no material");
        assert_eq!((m[0].name.as_str(), m[0].diffuse, m[0].dissolve), ("Base", Some([0.2, 0.3, 0.4]), Some(0.5)));
        assert_eq!(m[0].diffuse_texture.as_deref(), Some(".\\wood.jpg"), "options before the file skipped");
        assert_eq!((m[1].name.as_str(), m[1].diffuse, m[1].emissive), ("", Some([0.5; 3]), None));
        assert_eq!(m[2].diffuse_texture.as_deref(), Some("my texture.png"));
        assert_eq!(m[2].unknown_param.get("map_Ke").map(String::as_str), Some("glow.png"));
        assert_eq!((m[2].dissolve, m[2].diffuse), (Some(0.75), None), "a negative colour is not read");
        assert_eq!(names["with spaces"], 2);
    }
}
