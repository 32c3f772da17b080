//! A pipeline's layout: the order in which its groups, and in a whole pipeline its stages, are
//! handed to the driver. The driver lays the pipeline's code out in an order of its own making
//! from these, and that layout moves a set's trace time: on the H200 (driver 580) the same
//! modules with their stages in reverse order moved a masked model's time by up to 3.6% at
//! 16 spp, and GLSL/Rust from 0.991 to 1.006 at 1 spp (docs/measuring.md, *Places*). A place
//! therefore draws a layout of its own, as it draws its spacers, and the SBT's records follow
//! each group to where the layout put it: what a trace runs is the same in every layout.

use crate::vk::pipeline::{GroupDesc, StageDesc};
use ash::vk;
use twinray_shared::random::SplitMix64;

/// Which layout a pipeline is made with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayoutDraw {
    /// Groups in SBT order (raygen, misses, hit groups, callables, witnesses), and stages in the
    /// order of their modules.
    Sbt,
    /// The layout drawn for this place (`placement::place`).
    Place(u64),
}

/// The order of a pipeline's groups: `order[p]` is the group (in SBT order) at position `p`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    order: Vec<u32>,
}

impl Layout {
    /// The layout `draw` gives a pipeline of `groups` groups: a permutation drawn with a seed
    /// fixed per place, so that a command repeats its places exactly.
    pub fn new(draw: LayoutDraw, groups: usize) -> Layout {
        let mut order: Vec<u32> = (0..groups as u32).collect();
        if let LayoutDraw::Place(place) = draw {
            let mut rng = SplitMix64(SEED ^ place.wrapping_mul(0x9e37_79b9_7f4a_7c15));
            // Fisher-Yates: every order equally likely.
            for i in (1..order.len()).rev() {
                order.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
            }
        }
        Layout { order }
    }

    /// The groups in SBT order, laid out: the one at each position.
    pub fn groups(&self, groups: &[GroupDesc]) -> Vec<GroupDesc> {
        self.order.iter().map(|&g| groups[g as usize]).collect()
    }

    /// Where group `group` (in SBT order) lies in the laid-out pipeline.
    pub fn position(&self, group: u32) -> u32 {
        self.order.iter().position(|&g| g == group).expect("a group of the pipeline") as u32
    }

    /// SBT records naming groups in SBT order, renamed to their positions in the layout.
    pub fn records(&self, records: &[Vec<u32>; 4]) -> [Vec<u32>; 4] {
        records.clone().map(|region| region.iter().map(|&g| self.position(g)).collect())
    }
}

/// The seed of the layouts' draws, apart from the spacers' (`placement::spacer_sets`).
const SEED: u64 = 0x1a70_07d5_eed0_0053;

/// The stages of a whole pipeline in the order its laid-out `groups` first name them (a stage
/// no group names keeps its place after them), and the groups renumbered to match: a whole
/// pipeline's code follows its stages, not its groups.
///
/// An intersection stage gets an entry of its own for each any-hit stage it is paired with (none
/// being one): lavapipe (Mesa 25.0) builds an intersection stage once, with the any-hit stage of
/// the first group in the list that names it, and runs that pairing for every group that shares
/// the stage, so that a cutout object whose shape an uncut object also uses lost its holes
/// whenever the uncut object's group came first (docs/upstream/lavapipe-shared-intersection.md).
pub fn stages_in_group_order<'a>(
    stages: &[StageDesc<'a>],
    groups: &[GroupDesc],
) -> (Vec<StageDesc<'a>>, Vec<GroupDesc>) {
    // Each entry: a stage, and for an intersection stage the any-hit stage it is paired with.
    let mut order: Vec<(u32, u32)> = Vec::with_capacity(stages.len());
    let u = vk::SHADER_UNUSED_KHR;
    let keys = |g: &GroupDesc| -> [(u32, u32); 3] {
        match *g {
            GroupDesc::Procedural { intersection, closest_hit, any_hit } => {
                [(intersection, any_hit), (closest_hit, u), (any_hit, u)]
            }
            _ => members(g).map(|i| (i, u)),
        }
    };
    for g in groups {
        for key in keys(g) {
            if key.0 != u && !order.contains(&key) {
                order.push(key);
            }
        }
    }
    let unnamed: Vec<(u32, u32)> =
        (0..stages.len() as u32).filter(|i| !order.iter().any(|k| k.0 == *i)).map(|i| (i, u)).collect();
    order.extend(unnamed);
    let at = |key: (u32, u32)| {
        if key.0 == u {
            u
        } else {
            order.iter().position(|&k| k == key).expect("a stage of the pipeline") as u32
        }
    };
    let renumbered = groups
        .iter()
        .map(|g| {
            let [a, b, c] = keys(g).map(at);
            match *g {
                GroupDesc::General(_) => GroupDesc::General(a),
                GroupDesc::Triangles { .. } => GroupDesc::Triangles { closest_hit: a, any_hit: b },
                GroupDesc::Procedural { .. } => GroupDesc::Procedural { intersection: a, closest_hit: b, any_hit: c },
            }
        })
        .collect();
    (order.iter().map(|&(i, _)| stages[i as usize]).collect(), renumbered)
}

/// The stage indices a group names, unused ones included.
fn members(group: &GroupDesc) -> [u32; 3] {
    let u = vk::SHADER_UNUSED_KHR;
    match *group {
        GroupDesc::General(i) => [i, u, u],
        GroupDesc::Triangles { closest_hit, any_hit } => [closest_hit, any_hit, u],
        GroupDesc::Procedural { intersection, closest_hit, any_hit } => [intersection, closest_hit, any_hit],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stage(name: &'static str) -> StageDesc<'static> {
        StageDesc { name, stage: vk::ShaderStageFlags::MISS_KHR, spirv: &[], entry: c"main", specialization: None }
    }

    #[test]
    fn the_sbt_layout_keeps_every_group_where_it_is() {
        let layout = Layout::new(LayoutDraw::Sbt, 5);
        assert_eq!((0..5).map(|g| layout.position(g)).collect::<Vec<_>>(), vec![0, 1, 2, 3, 4]);
    }

    #[test]
    fn a_place_draws_a_permutation_of_its_own_and_repeats_it() {
        let draws: Vec<Layout> = (0..50).map(|p| Layout::new(LayoutDraw::Place(p), 6)).collect();
        for d in &draws {
            let mut sorted = d.order.clone();
            sorted.sort();
            assert_eq!(sorted, (0..6).collect::<Vec<_>>(), "a permutation");
        }
        assert_eq!(draws[7], Layout::new(LayoutDraw::Place(7), 6), "a place repeats its draw");
        let distinct = draws.iter().map(|d| d.order.clone()).collect::<std::collections::BTreeSet<_>>().len();
        assert!(distinct > 30, "places draw different layouts: {distinct} of 50");
        // Every group reaches every position: no position is left to SBT order.
        for g in 0..6 {
            let positions: std::collections::BTreeSet<u32> = draws.iter().map(|d| d.position(g)).collect();
            assert_eq!(positions.len(), 6, "group {g} took positions {positions:?}");
        }
    }

    #[test]
    fn records_follow_their_groups() {
        let u = vk::SHADER_UNUSED_KHR;
        let groups = [
            GroupDesc::General(0),
            GroupDesc::General(1),
            GroupDesc::Triangles { closest_hit: 2, any_hit: u },
            GroupDesc::Triangles { closest_hit: 2, any_hit: 3 },
        ];
        let records = [vec![0], vec![1], vec![2, 3], vec![]];
        for place in 0..20 {
            let layout = Layout::new(LayoutDraw::Place(place), groups.len());
            let laid = layout.groups(&groups);
            let renamed = layout.records(&records);
            for (region, new) in records.iter().zip(&renamed) {
                let before: Vec<GroupDesc> = region.iter().map(|&g| groups[g as usize]).collect();
                let after: Vec<GroupDesc> = new.iter().map(|&p| laid[p as usize]).collect();
                assert_eq!(before, after, "place {place}: a record names another group");
            }
        }
    }

    #[test]
    fn stages_follow_the_groups_that_name_them() {
        let u = vk::SHADER_UNUSED_KHR;
        let stages = [stage("raygen"), stage("miss"), stage("isec"), stage("chit"), stage("ahit"), stage("spare")];
        let groups = [
            GroupDesc::Procedural { intersection: 2, closest_hit: 3, any_hit: 4 },
            GroupDesc::General(1),
            GroupDesc::General(0),
            GroupDesc::Procedural { intersection: 2, closest_hit: 3, any_hit: u },
            GroupDesc::Triangles { closest_hit: 3, any_hit: 4 },
        ];
        let (laid, renumbered) = stages_in_group_order(&stages, &groups);
        let names: Vec<&str> = laid.iter().map(|s| s.name).collect();
        // The intersection stage paired with no any-hit stage is an entry of its own.
        assert_eq!(names, ["isec", "chit", "ahit", "miss", "raygen", "isec", "spare"]);
        for (before, after) in groups.iter().zip(&renumbered) {
            fn name<'a>(g: &GroupDesc, all: &[StageDesc<'a>]) -> [&'a str; 3] {
                members(g).map(|i| if i == vk::SHADER_UNUSED_KHR { "-" } else { all[i as usize].name })
            }
            assert_eq!(name(before, &stages), name(after, &laid), "a group names other stages");
        }
        let isec = |g: &GroupDesc| match g {
            GroupDesc::Procedural { intersection, .. } => *intersection,
            _ => unreachable!(),
        };
        assert_ne!(isec(&renumbered[0]), isec(&renumbered[3]), "one intersection entry per any-hit pairing");
    }
}
