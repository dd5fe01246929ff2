//! What MuJoCo 4.0.0 refuses of the shape of a mesh written inline without faces
//! (its faces are then its convex hull's): vertices all at one point, on one line or
//! in one plane (`mjCMesh::MakeGraph`'s checks before its hull is computed), and a
//! hull whose surface or volume is too small once scaled, where that follows
//! without computing the hull (a bound on its area, a zero scale).

use super::At;

/// MuJoCo's `mjMINVAL`.
const MINVAL: f64 = 1e-15;

/// What MuJoCo says of the mesh `name` whose vertices (as written, 3 numbers each,
/// at least 4, all finite) have no faces, if it refuses it for its shape.
pub(super) fn message(at: &At<'_, '_>, vert: &[f64]) -> Option<String> {
    // MuJoCo reads vertices in single precision.
    let v: Vec<[f64; 3]> = vert
        .chunks(3)
        .map(|p| [p[0] as f32 as f64, p[1] as f32 as f64, p[2] as f32 as f64])
        .collect();
    let name = at.name();
    if let Some(shape) = degenerate(&v) {
        let advice = match shape {
            "colocated" => "a small sphere",
            "collinear" => "a thin capsule",
            _ => "a primitive geom type (plane or thin box)",
        };
        return Some(format!(
            "mesh '{name}' has {shape} vertices, cannot compute convex hull. Consider using {advice} instead"
        ));
    }
    // The shape as scaled (a rotation would change the bounds below).
    if at.floats("refquat").is_some_and(|q| q.len() >= 4 && q[..4] != [1.0, 0.0, 0.0, 0.0]) {
        return None;
    }
    let s = at.floats("scale").unwrap_or_default();
    let s = [0, 1, 2].map(|i| s.get(i).copied().unwrap_or(1.0));
    let scaled: Vec<[f64; 3]> = v.iter().map(|p| [0, 1, 2].map(|i| p[i] * s[i])).collect();
    // The hull's surface is no larger than its bounding box's.
    let (lo, hi) = bounds(&scaled);
    let [a, b, c] = [0, 1, 2].map(|i| hi[i] - lo[i]);
    if 2.0 * (a * b + b * c + c * a) * (1.0 + 1e-6) < MINVAL {
        return Some(format!("mesh surface area is too small: {name}"));
    }
    // The hull's volume is no larger than its bounding box's (exactly zero when a
    // scale is zero: every coordinate on that axis is), less what rounding may add;
    // its surface no smaller than twice its shadow on each axis plane (less the faces
    // MuJoCo ignores as too small, at most two per vertex, each under MINVAL / 2).
    if at.str("inertia") == Some("shell") || at.int("maxhullvert").is_some_and(|n| n != -1) {
        return None;
    }
    let far = scaled.iter().flatten().fold(0f64, |m, x| m.max(x.abs()));
    let area = 2.0 * (a * b + b * c + c * a);
    let volume = if s.contains(&0.0) { 0.0 } else { a * b * c * (1.0 + 1e-6) + 1e-9 * area * far };
    (volume < MINVAL).then_some(())?;
    let shadow = (0..3)
        .map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            hull_area(scaled.iter().map(|p| [p[j], p[k]]).collect())
        })
        .fold(0f64, f64::max);
    (2.0 * shadow * (1.0 - 1e-6) >= (v.len() as f64 + 2.0) * MINVAL)
        .then(|| format!("mesh volume is too small: {name} . Try setting inertia to shell"))
}

/// `colocated`, `collinear` or `coplanar` as MuJoCo finds them, from vertex 0.
fn degenerate(v: &[[f64; 3]]) -> Option<&'static str> {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let Some((v1, len1)) = (1..v.len())
        .map(|i| (i, dot(sub(v[i], v[0]), sub(v[i], v[0])).sqrt()))
        .find(|(_, l)| *l > MINVAL)
    else {
        return Some("colocated");
    };
    let edge1 = sub(v[v1], v[0]);
    let mut normal = None;
    for (i, p) in v.iter().enumerate().skip(1) {
        if i == v1 {
            continue;
        }
        let edge2 = sub(*p, v[0]);
        let len2 = dot(edge2, edge2).sqrt();
        if len2 < MINVAL {
            continue;
        }
        let n = [
            edge1[1] * edge2[2] - edge1[2] * edge2[1],
            edge1[2] * edge2[0] - edge1[0] * edge2[2],
            edge1[0] * edge2[1] - edge1[1] * edge2[0],
        ];
        let norm = dot(n, n).sqrt();
        if norm > MINVAL * len1 * len2 {
            normal = Some([n[0] / norm, n[1] / norm, n[2] / norm]);
            break;
        }
    }
    let Some(normal) = normal else { return Some("collinear") };
    let d = dot(normal, v[0]);
    v.iter().all(|p| (dot(normal, *p) - d).abs() <= MINVAL * len1).then_some("coplanar")
}

/// The least and greatest coordinates.
fn bounds(v: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in v {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    (lo, hi)
}

/// The area of the convex hull of points in a plane (monotone chain).
fn hull_area(mut p: Vec<[f64; 2]>) -> f64 {
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return 0.0;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let points: Box<dyn Iterator<Item = &[f64; 2]>> =
            if pass == 0 { Box::new(p.iter()) } else { Box::new(p.iter().rev()) };
        for q in points {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], *q) <= 0.0
            {
                hull.pop();
            }
            hull.push(*q);
        }
        hull.pop();
    }
    let n = hull.len();
    (0..n).map(|i| cross([0.0, 0.0], hull[i], hull[(i + 1) % n])).sum::<f64>().abs() / 2.0
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_outline_area_is_its_convex_hulls() {
        let square = vec![[0.0, 0.0], [1.0, 0.0], [0.5, 0.5], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
        assert_eq!(super::hull_area(square), 1.0);
        assert_eq!(super::hull_area(vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]), 0.0);
    }
}
