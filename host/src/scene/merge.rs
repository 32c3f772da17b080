//! Which objects share a TLAS instance. A run of consecutive objects placed alike (the same
//! transform, mask, hit group and facing) whose shapes are all meshes is traced as one
//! instance of one BLAS that holds each object's mesh as a geometry, in order: the stages find
//! a hit's object as its instance id plus its geometry index
//! (`twinray_shared::bindings::mesh_object`), so the instance takes the slot of the run's
//! first object and the slots of the others are left inactive. A glTF mesh's primitives are
//! such a run: one BLAS per mesh however many primitives it has, shared by every node that
//! places it. Everything else (procedural shapes, lone meshes) is a run of one, its shape's
//! own BLAS.

use super::build::{BlasDesc, SceneData};

/// Objects `first ..` (as many as `blases` holds) traced as one instance of the BLAS holding
/// `blases` (indices into `SceneData::blases`), geometry `k` object `first + k`'s.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Run {
    pub first: usize,
    pub blases: Vec<usize>,
}

/// The device's limits on one BLAS: geometries, and primitives over all of them.
#[derive(Clone, Copy, Debug)]
pub struct BlasLimits {
    pub geometries: u64,
    pub primitives: u64,
}

/// The runs of `data`'s objects, in order, each object in one. `share(first, object)` says
/// whether `object` may join the run `first` starts, beyond being placed alike: not where
/// either moves on its own (a moving scene's objects of different bodies) or has its mesh
/// posed, which `share(object, object)` false keeps alone.
pub fn runs(data: &SceneData, share: impl Fn(usize, usize) -> bool, limits: BlasLimits) -> Vec<Run> {
    // Each run, with its primitives where it is a run of meshes that may take more.
    let mut runs: Vec<(Run, Option<u64>)> = Vec::new();
    for (object, instance) in data.instances.iter().enumerate() {
        let mesh = match &data.blases[instance.blas] {
            BlasDesc::Triangles { index_count, .. } if share(object, object) => Some(u64::from(*index_count / 3)),
            _ => None,
        };
        if let (Some(count), Some((run, Some(primitives)))) = (mesh, runs.last_mut()) {
            let first = &data.instances[run.first];
            let alike = first.object_to_world == instance.object_to_world
                && (first.mask, first.hit_group, first.single_sided)
                    == (instance.mask, instance.hit_group, instance.single_sided);
            let fits = (run.blases.len() as u64) < limits.geometries && *primitives + count <= limits.primitives;
            if alike && fits && share(run.first, object) {
                run.blases.push(instance.blas);
                *primitives += count;
                continue;
            }
        }
        runs.push((Run { first: object, blases: vec![instance.blas] }, mesh));
    }
    runs.into_iter().map(|(run, _)| run).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{MeshFiles, Scene};

    const WIDE: BlasLimits = BlasLimits { geometries: 1 << 24, primitives: 1 << 29 };

    /// A scene of `objects` (TOML `[[objects]]` bodies) over two box meshes, a sphere and two
    /// materials, one of them emissive.
    fn scene(objects: &[&str]) -> SceneData {
        let mut text = String::from(
            "name = \"runs\"\n[image]\nwidth = 8\nheight = 8\n[camera]\neye = [0.0, 0.0, 9.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n\
             [materials.m]\nkind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\n\
             [materials.glow]\nkind = \"emissive\"\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n\
             [shapes.a]\nkind = \"mesh\"\nbuiltin = \"box\"\n[shapes.b]\nkind = \"mesh\"\nbuiltin = \"pyramid\"\n\
             [shapes.ball]\nkind = \"sphere\"\nradius = 1.0\n",
        );
        for o in objects {
            text += &format!("[[objects]]\n{o}\n");
        }
        Scene::parse(&text, "runs", MeshFiles::Builtin).expect("the scene").build()
    }

    fn firsts(runs: &[Run]) -> Vec<(usize, usize)> {
        runs.iter().map(|r| (r.first, r.blases.len())).collect()
    }

    #[test]
    fn meshes_placed_alike_in_a_row_share_one_instance() {
        let data = scene(&[
            "shape = \"a\"\nmaterial = \"m\"",
            "shape = \"b\"\nmaterial = \"m\"",
            "shape = \"a\"\nmaterial = \"m\"",
            // Moved: a run of its own, which the next object joins.
            "shape = \"a\"\nmaterial = \"m\"\ntranslate = [2.0, 0.0, 0.0]",
            "shape = \"b\"\nmaterial = \"m\"\ntranslate = [2.0, 0.0, 0.0]",
            // A procedural shape stands alone, and the mesh after it starts afresh.
            "shape = \"ball\"\nmaterial = \"m\"\ntranslate = [2.0, 0.0, 0.0]",
            "shape = \"b\"\nmaterial = \"m\"\ntranslate = [2.0, 0.0, 0.0]",
            // Another mask (an emitter): apart.
            "shape = \"a\"\nmaterial = \"glow\"\ntranslate = [2.0, 0.0, 0.0]",
        ]);
        let runs = runs(&data, |_, _| true, WIDE);
        assert_eq!(firsts(&runs), [(0, 3), (3, 2), (5, 1), (6, 1), (7, 1)]);
        // Geometry k of a run is object first + k's shape.
        for run in &runs {
            for (k, blas) in run.blases.iter().enumerate() {
                assert_eq!(*blas, data.instances[run.first + k].blas);
            }
        }
    }

    #[test]
    fn objects_kept_alone_and_the_device_limits_split_runs() {
        let objects = ["shape = \"a\"\nmaterial = \"m\""; 5];
        let data = scene(&objects);
        assert_eq!(firsts(&runs(&data, |_, _| true, WIDE)), [(0, 5)]);
        assert_eq!(firsts(&runs(&data, |a, b| a != 2 && b != 2, WIDE)), [(0, 2), (2, 1), (3, 2)]);
        assert_eq!(firsts(&runs(&data, |_, _| false, WIDE)), [(0, 1), (1, 1), (2, 1), (3, 1), (4, 1)]);
        let two = BlasLimits { geometries: 2, ..WIDE };
        assert_eq!(firsts(&runs(&data, |_, _| true, two)), [(0, 2), (2, 2), (4, 1)]);
        // A box is 12 triangles: 30 take two boxes a BLAS.
        let thirty = BlasLimits { primitives: 30, ..WIDE };
        assert_eq!(firsts(&runs(&data, |_, _| true, thirty)), [(0, 2), (2, 2), (4, 1)]);
    }
}
