use super::*;

fn placed(centre: Vec3, half: f32) -> Placed {
    Placed { bounds: Aabb { min: centre - half, max: centre + half }, translation: centre }
}

fn toward(origin: Vec3, target: Vec3) -> LaunchRay {
    LaunchRay { origin, direction: (target - origin).normalize(), t_min: 0.0, t_max: 1e30 }
}

/// Where each ray is launched, by ray, checking that every ray is in exactly one launch.
fn launched_at(rays: &[LaunchRay], placed: &[Placed]) -> Vec<Vec3> {
    let launches = launches(rays, placed);
    assert!(launches.len() <= MAX_LAUNCHES && launches.iter().all(|l| !l.rays.is_empty()));
    let mut at = vec![None; rays.len()];
    for l in &launches {
        for &i in &l.rays {
            assert!(at[i].replace(l.origin).is_none(), "ray {i} is in two launches");
        }
    }
    at.into_iter().enumerate().map(|(i, o)| o.unwrap_or_else(|| panic!("ray {i} is in no launch"))).collect()
}

/// The rounding magnitude of `ray` at `c` over its own at its start, for the instance it is
/// centred for.
fn growth(ray: &LaunchRay, placed: &[Placed], c: Vec3) -> f64 {
    let need = Need::new(ray, placed);
    if need.limit.is_infinite() {
        return 0.0;
    }
    need.rounding_at(c) / need.rounding_at(ray.origin)
}

/// Rays 3.5 to 5.5 units from a mesh 3e4 out and a silhouette from 440 units all start within
/// an eighth of their magnitude of each other; centred at their mean, the near ones were
/// rounded 30 times coarser than alone. Centred for what they meet, none grows past the slack.
#[test]
fn near_rays_never_pay_for_far_ones_that_start_nearby() {
    let mesh = placed(Vec3::new(30000.0, 1200.0, -8000.0), 1.0);
    let mut rays: Vec<LaunchRay> = (0..300)
        .map(|i| {
            let a = i as f32 * 0.37;
            let r = 3.5 + 2.0 * (i % 7) as f32 / 6.0;
            toward(mesh.translation + r * Vec3::new(a.cos(), (0.3 * a).sin(), a.sin()), mesh.translation)
        })
        .collect();
    rays.extend((0..100).map(|i| {
        let o = mesh.translation + Vec3::new(440.0, 0.02 * i as f32 - 1.0, 0.5);
        LaunchRay { origin: o, direction: -Vec3::X, t_min: 0.0, t_max: 1e30 }
    }));
    let at = launched_at(&rays, &[mesh]);
    for (ray, c) in rays.iter().zip(&at) {
        assert!(exact(ray.origin, *c), "{} at {c}", ray.origin);
        assert!(growth(ray, &[mesh], *c) <= SLACK, "{} at {c}: {}", ray.origin, growth(ray, &[mesh], *c));
    }
}

/// Camera rays from one eye to a grid of small instances share a launch at the eye; rays from
/// all around one instance share a launch at its translation.
#[test]
fn rays_that_start_together_or_meet_one_instance_share_a_launch() {
    let grid: Vec<Placed> =
        (0..25).map(|i| placed(Vec3::new(5000.0 + (i % 5) as f32, 3000.0 + (i / 5) as f32, 100.0), 0.3)).collect();
    let eye = Vec3::new(5002.0, 3002.0, 140.0);
    let camera: Vec<LaunchRay> = grid.iter().map(|p| toward(eye, p.translation)).collect();
    assert_eq!(launches(&camera, &grid), vec![Launch { origin: eye, rays: (0..25).collect() }]);
    let ball = grid[7];
    let around: Vec<LaunchRay> = (0..64)
        .map(|i| {
            let (a, b) = (i as f32 * 0.7, i as f32 * 0.31);
            toward(ball.translation + 0.6 * Vec3::new(a.cos() * b.cos(), b.sin(), a.sin() * b.cos()), ball.translation)
        })
        .collect();
    assert_eq!(launches(&around, &[ball]), vec![Launch { origin: ball.translation, rays: (0..64).collect() }]);
}

/// A ray that crosses a large box to a small mesh beside it is centred for the mesh: the
/// instance whose translation lies nearest its start sets the tightest bound.
#[test]
fn a_ray_is_centred_for_the_nearest_instance_it_can_hit() {
    let floor = placed(Vec3::new(20000.0, -500.0, 0.0), 500.0);
    let mesh = placed(Vec3::new(20300.0, 0.5, 20.0), 0.5);
    let ray = toward(Vec3::new(20300.0, 3.0, 24.0), mesh.translation);
    assert_eq!(key(&ray, &[floor, mesh]), Some(1));
    let at = launched_at(&[ray], &[floor, mesh]);
    assert!(growth(&ray, &[floor, mesh], at[0]) <= SLACK);
    // Aimed away from both, it meets neither and stays at the world origin.
    let away = LaunchRay { direction: Vec3::Y, ..ray };
    assert_eq!(key(&away, &[floor, mesh]), None);
    assert_eq!(launched_at(&[away], &[floor, mesh]), vec![Vec3::ZERO]);
}

#[test]
fn rays_the_world_origin_serves_stay_there() {
    // A sheet at the world origin seen from 100 units: its translation is the world origin.
    let sheet = placed(Vec3::ZERO, 0.5);
    let rays: Vec<LaunchRay> = (0..64)
        .map(|i| toward(100.0 * Vec3::new((i as f32 * 0.1).cos(), 0.0, (i as f32 * 0.1).sin()), Vec3::ZERO))
        .collect();
    assert!(launched_at(&rays, &[sheet]).iter().all(|&c| c == Vec3::ZERO));
    // Rays from the world origin to an object 10 units out are rounded at 10 either way.
    assert_eq!(launched_at(&[toward(Vec3::ZERO, Vec3::X * 10.0)], &[placed(Vec3::X * 10.0, 1.0)]), vec![Vec3::ZERO]);
}

#[test]
fn two_groups_far_apart_are_launched_apart() {
    let a = placed(Vec3::new(95.0, 0.0, 3.0), 0.5);
    let b = placed(Vec3::new(7000.0, -5000.0, 6500.0), 0.5);
    let near: Vec<LaunchRay> = (0..50).map(|i| toward(Vec3::new(100.0, 0.01 * i as f32, 3.0), a.translation)).collect();
    let far: Vec<LaunchRay> =
        (0..50).map(|i| toward(Vec3::new(7000.0 + 0.02 * i as f32, -5000.0, 6490.0), b.translation)).collect();
    let rays: Vec<LaunchRay> = near.iter().chain(&far).copied().collect();
    let at = launched_at(&rays, &[a, b]);
    assert_ne!(at[0], at[50]);
    for (ray, c) in rays.iter().zip(&at) {
        assert!(exact(ray.origin, *c) && growth(ray, &[a, b], *c) <= SLACK, "{} at {c}", ray.origin);
    }
}

/// Random instances and rays over many magnitudes: every ray and what it can hit move exactly,
/// and, while the launches are within the cap, none is rounded more than the slack allows but
/// where no exact origin would do that, and then no more than at the world origin.
#[test]
fn random_rays_move_exactly_and_within_the_slack() {
    let mut rng = twinray_shared::random::SplitMix64(90);
    let mut unit = || Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
    let mut capped_cases = 0;
    for case in 0..60 {
        let (mut rays, mut objects) = (Vec::new(), Vec::new());
        for _ in 0..1 + case % 5 {
            let scale = 10f32.powf(4.0 * unit().x + 2.0);
            let centre = unit() * 2.0 * scale;
            let size = scale * 10f32.powf(-4.0 * (unit().y + 0.5));
            objects.push(placed(centre, size));
            for _ in 0..40 {
                let from = centre + unit().normalize() * size * 10f32.powf(3.0 * (unit().z + 0.5));
                rays.push(toward(from, centre + unit() * size));
            }
        }
        let launches = launches(&rays, &objects);
        let capped = launches.len() == MAX_LAUNCHES;
        capped_cases += usize::from(capped);
        for (ray, c) in rays.iter().zip(launched_at(&rays, &objects)) {
            let need = Need::new(ray, &objects);
            assert!(need.exact_at(c), "case {case}: {} at {c}", ray.origin);
            let within = growth(ray, &objects, c) <= SLACK;
            let no_worse = need.rounding_at(c) <= need.rounding_at(Vec3::ZERO);
            let could = need.served_by(need.own_origin()) || need.served_by(ray.origin);
            assert!(capped || within || (!could && no_worse), "case {case}: {} at {c}", ray.origin);
        }
    }
    // The bound was checked: few cases need more launches than the cap.
    assert!(capped_cases <= 3, "{capped_cases} of 60 cases needed more than {MAX_LAUNCHES} launches");
}

/// Copies of a ray (a probe timed over its rays repeated) go where the ray goes.
#[test]
fn copies_of_a_ray_share_its_launch() {
    let a = placed(Vec3::new(9000.0, 0.0, 0.0), 1.0);
    let rays: Vec<LaunchRay> = (0..5).map(|i| toward(Vec3::new(9003.0, 0.1 * i as f32, 2.0), a.translation)).collect();
    let copies: Vec<LaunchRay> = rays.iter().cycle().take(23).copied().collect();
    let at = launched_at(&copies, &[a]);
    for (i, c) in at.iter().enumerate() {
        assert_eq!(*c, at[i % 5], "copy {i}");
    }
}
