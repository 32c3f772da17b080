//! Where a mesh's triangles meet. A ray across a shared edge or vertex passes within float
//! noise of each triangle's edge, so each triangle alone calls it ambiguous; but where the
//! mesh is closed it leaves no gap (Vulkan requires the triangle test to be watertight), so the
//! ray crosses the surface there. This decides such rays: a hit, when every edge the crossing
//! is near is shared by two of the triangles it is near, and the ray crosses all of them from
//! the same side and not at a grazing angle. Anything else stays ambiguous.

use super::ray::RefRay;
use super::shapes::RefShape;
use glam::DVec3;

/// Smallest |cos| between the ray and each triangle's normal for a crossing to be decided: a
/// grazing ray may slip along the surface between triangles that fold.
const MIN_COSINE: f64 = 0.05;

/// A ray's crossing of one triangle's plane.
struct Crossing {
    k: usize,
    t: f64,
    normal: DVec3,
    /// Barycentric weights of the corners, and the band within which one counts as 0.
    weights: [f64; 3],
    band: f64,
    corners: [DVec3; 3],
}

/// `ray` across triangle `k` of corners `p`, as `shapes::triangle` computes it; `Err` with
/// where along the ray the ray grazes it (the crossing is no use): its plane's crossing, or
/// where the triangle starts for a ray in its plane.
fn crossing(ray: &RefRay, k: usize, p: [DVec3; 3]) -> Result<Crossing, f64> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let normal = e1.cross(e2);
    let h = ray.direction.cross(e2);
    let det = e1.dot(h);
    if det == 0.0 {
        let along = |c: &DVec3| (*c - ray.origin).dot(ray.direction) / ray.direction.length_squared();
        return Err(p.iter().map(along).fold(f64::MAX, f64::min));
    }
    let s = ray.origin - p[0];
    let (u, q) = (s.dot(h) / det, s.cross(e1));
    let (v, t) = (ray.direction.dot(q) / det, e2.dot(q) / det);
    if ray.direction.normalize().dot(normal.normalize()).abs() < MIN_COSINE {
        return Err(t);
    }
    let band = ray.edge_band(t, normal) / normal.length().sqrt().max(1e-30);
    Ok(Crossing { k, t, normal, weights: [1.0 - u - v, u, v], band, corners: p })
}

/// The edges of `c` the crossing is within noise of, each as its two corners.
fn near_edges(c: &Crossing) -> impl Iterator<Item = [DVec3; 2]> + '_ {
    (0..3).filter(|&i| c.weights[i] <= c.band).map(|i| [c.corners[(i + 1) % 3], c.corners[(i + 2) % 3]])
}

fn same_edge(a: [DVec3; 2], b: [DVec3; 2]) -> bool {
    (a[0] == b[0] && a[1] == b[1]) || (a[0] == b[1] && a[1] == b[0])
}

/// Where `ray` crosses the mesh `shapes` at the triangles `unsure` (each ambiguous alone), if
/// the nearest of those crossings is decided: `Some(Some((k, t, normal)))`, a hit on triangle
/// `k`; `Some(None)`, no crossing within the ray's reach; `None`, ambiguous.
pub fn across(shapes: &[RefShape], unsure: &[usize], ray: &RefRay) -> Option<Option<(usize, f64, DVec3)>> {
    let (mut crossings, mut grazed) = (Vec::with_capacity(unsure.len()), Vec::new());
    for &k in unsure {
        let RefShape::Triangle { p } = shapes[k] else { return None };
        match crossing(ray, k, p) {
            Ok(c) => crossings.push(c),
            Err(start) => grazed.push(start),
        }
    }
    crossings.sort_by(|a, b| a.t.total_cmp(&b.t));
    let nearest = crossings.first()?.t;
    let tol_t = |t: f64| ray.tolerance(t) / ray.direction.length();
    // A triangle the ray grazes is no help; it must lie wholly beyond the crossing.
    if grazed.iter().any(|&start| start <= nearest + 4.0 * tol_t(nearest)) {
        return None;
    }
    if nearest > ray.t_max + tol_t(nearest) {
        return Some(None);
    }
    if (nearest - ray.t_min).abs() <= tol_t(nearest) || (nearest - ray.t_max).abs() <= tol_t(nearest) {
        return None;
    }
    // Past t_min: the crossings behind the origin do not count.
    let group: Vec<&Crossing> = crossings.iter().filter(|c| (c.t - nearest).abs() <= 4.0 * tol_t(c.t)).collect();
    if nearest < ray.t_min {
        return if crossings.iter().all(|c| c.t < ray.t_min - tol_t(c.t)) { Some(None) } else { None };
    }
    let side = group[0].normal.dot(ray.direction).signum();
    if group.iter().any(|c| c.normal.dot(ray.direction).signum() != side) {
        return None;
    }
    let shared =
        |c: &Crossing, edge: [DVec3; 2]| group.iter().any(|o| o.k != c.k && near_edges(o).any(|e| same_edge(e, edge)));
    if group.iter().any(|c| near_edges(c).any(|e| !shared(c, e))) {
        return None;
    }
    let inside = |c: &&&Crossing| c.weights.iter().copied().fold(f64::MAX, f64::min);
    let best = group.iter().max_by(|a, b| inside(a).total_cmp(&inside(b)))?;
    Some(Some((best.k, best.t, best.normal.normalize())))
}
