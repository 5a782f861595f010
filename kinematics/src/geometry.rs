//! Exact distances and penetration depths between segments (capsule cores) and oriented boxes,
//! in f64 and without a physics engine.
//!
//! Every point and pose is in one common frame of the caller's choice (`world` for the env's
//! free-space checks); lengths are metres. A capsule is a segment swept by a radius, so its
//! queries are the segment's queries shifted by the radius (capsule–capsule is
//! [`crate::collision::segment_distance`]).

use nalgebra::{Isometry3, Point3, Vector3};

/// Below this squared norm \[m²\] a direction (segment or edge cross product) is treated as zero.
const DEGENERATE: f64 = 1e-18;

/// An oriented box: centre and axes given by `pose` (the box frame in the common frame), extent
/// `±half_extents[k]` \[m\] along box axis `k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid {
    /// The box frame (centre, axes) in the common frame.
    pub pose: Isometry3<f64>,
    /// Half sizes along the box's x, y, z \[m\]; non-negative.
    pub half_extents: [f64; 3],
}

impl Cuboid {
    /// A box of half sizes `half_extents` \[m\] whose frame is `pose`.
    pub fn new(pose: Isometry3<f64>, half_extents: [f64; 3]) -> Cuboid {
        Cuboid { pose, half_extents }
    }

    /// The box's three unit axes in the common frame.
    fn axes(&self) -> [Vector3<f64>; 3] {
        let m = self.pose.rotation.to_rotation_matrix();
        [0, 1, 2].map(|k| m.matrix().column(k).into_owned())
    }

    /// Radius \[m\] of the projection onto the unit direction `l` of a box with `axes`.
    fn projected_radius(&self, axes: &[Vector3<f64>; 3], l: &Vector3<f64>) -> f64 {
        (0..3)
            .map(|k| self.half_extents[k] * axes[k].dot(l).abs())
            .sum()
    }

    /// Distance \[m\] from `p` (box frame) to the box; 0 inside.
    fn local_point_distance_squared(&self, p: &Vector3<f64>) -> f64 {
        (0..3)
            .map(|k| (p[k].abs() - self.half_extents[k]).max(0.0).powi(2))
            .sum()
    }
}

/// Distance \[m\] between the segment `a → b` and the box; 0 when the segment touches or enters
/// it. Exact: in the box frame the squared distance from `a + t (b − a)` is a convex piecewise
/// quadratic in `t` whose pieces change only where a coordinate crosses a face plane, so its
/// minimum is at a crossing, an end, or the vertex of one piece's parabola.
pub fn segment_box_distance(a: [f64; 3], b: [f64; 3], cuboid: &Cuboid) -> f64 {
    let p0 = cuboid.pose.inverse_transform_point(&Point3::from(a)).coords;
    let p1 = cuboid.pose.inverse_transform_point(&Point3::from(b)).coords;
    let d = p1 - p0;
    let h = cuboid.half_extents;
    let at = |t: f64| cuboid.local_point_distance_squared(&(p0 + d * t));
    // Ends and face-plane crossings, sorted: the breakpoints of the piecewise quadratic.
    let mut ts = [1.0; 8];
    ts[0] = 0.0;
    let mut n = 2;
    for k in 0..3 {
        if d[k].abs() > 0.0 {
            for s in [-1.0, 1.0] {
                let t = (s * h[k] - p0[k]) / d[k];
                if t > 0.0 && t < 1.0 {
                    ts[n] = t;
                    n += 1;
                }
            }
        }
    }
    let ts = &mut ts[..n];
    ts.sort_unstable_by(f64::total_cmp);
    let mut best = ts.iter().map(|&t| at(t)).fold(f64::INFINITY, f64::min);
    // On each piece, minimise the quadratic Σ over outside coordinates of (p0ₖ + t dₖ ∓ hₖ)².
    for w in ts.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        let mid = p0 + d * (0.5 * (t0 + t1));
        let (mut aa, mut bb, mut outside) = (0.0, 0.0, false);
        for k in 0..3 {
            let c = if mid[k] > h[k] {
                p0[k] - h[k]
            } else if mid[k] < -h[k] {
                p0[k] + h[k]
            } else {
                continue;
            };
            aa += d[k] * d[k];
            bb += d[k] * c;
            outside = true;
        }
        if !outside {
            // This piece runs inside the box (its ends may round to just outside a face).
            return 0.0;
        }
        if aa > 0.0 {
            best = best.min(at((-bb / aa).clamp(t0, t1)));
        }
    }
    best.sqrt()
}

/// How deep \[m\] the segment `a → b` reaches into the box: the shortest translation that moves
/// it out (0 when it does not touch the box's interior). Separating-axis test over the box's
/// three face normals and the segment's direction crossed with each box edge.
pub fn segment_box_penetration(a: [f64; 3], b: [f64; 3], cuboid: &Cuboid) -> f64 {
    let (a, b) = (Vector3::from(a), Vector3::from(b));
    let centre = 0.5 * (a + b) - cuboid.pose.translation.vector;
    let half = 0.5 * (b - a);
    let axes = cuboid.axes();
    let mut depth = f64::INFINITY;
    let mut try_axis = |l: Vector3<f64>| {
        let overlap =
            cuboid.projected_radius(&axes, &l) + half.dot(&l).abs() - centre.dot(&l).abs();
        depth = depth.min(overlap);
    };
    for axis in axes {
        try_axis(axis);
        let l = half.cross(&axis);
        if l.norm_squared() > DEGENERATE {
            try_axis(l.normalize());
        }
    }
    depth.max(0.0)
}

/// Signed distance \[m\] from the segment `a → b` to the box: the distance when apart, minus the
/// penetration depth when the segment enters it. A capsule of radius `r` on the segment has
/// signed distance `segment_box_signed_distance − r` (exact: the capsule is the segment
/// Minkowski-summed with a ball).
pub fn segment_box_signed_distance(a: [f64; 3], b: [f64; 3], cuboid: &Cuboid) -> f64 {
    let distance = segment_box_distance(a, b, cuboid);
    if distance > 0.0 {
        distance
    } else {
        -segment_box_penetration(a, b, cuboid)
    }
}

/// The largest gap \[m\] between the boxes' projections over the 15 separating axes (the 3 + 3
/// face normals and the 9 edge cross products; near-parallel edge pairs, whose cross product
/// vanishes, are covered by the face normals and skipped). Positive: the boxes are apart by at
/// least this much (a lower bound on their distance, exact when a face normal separates
/// them). Negative: they overlap and this is minus the penetration depth (exact: the shortest
/// translation separating two boxes is along one of these axes).
pub fn box_box_separation(a: &Cuboid, b: &Cuboid) -> f64 {
    let t = b.pose.translation.vector - a.pose.translation.vector;
    let (axes_a, axes_b) = (a.axes(), b.axes());
    let mut separation = f64::NEG_INFINITY;
    let mut try_axis = |l: Vector3<f64>| {
        let gap =
            t.dot(&l).abs() - a.projected_radius(&axes_a, &l) - b.projected_radius(&axes_b, &l);
        separation = separation.max(gap);
    };
    for (u, v) in axes_a.iter().zip(&axes_b) {
        try_axis(*u);
        try_axis(*v);
    }
    for u in &axes_a {
        for v in &axes_b {
            let l = u.cross(v);
            if l.norm_squared() > DEGENERATE {
                try_axis(l.normalize());
            }
        }
    }
    separation
}

/// Penetration depth \[m\] of two overlapping boxes (`None` when they are apart or only touch).
pub fn box_box_penetration(a: &Cuboid, b: &Cuboid) -> Option<f64> {
    let separation = box_box_separation(a, b);
    (separation < 0.0).then_some(-separation)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random_box(rng: &mut ChaCha8Rng, spread: f64) -> Cuboid {
        let c = [0; 3].map(|_| rng.random_range(-spread..spread));
        let r = [0; 3].map(|_| rng.random_range(-3.2..3.2));
        Cuboid::new(
            Isometry3::from_parts(
                Translation3::new(c[0], c[1], c[2]),
                UnitQuaternion::from_euler_angles(r[0], r[1], r[2]),
            ),
            [0; 3].map(|_| rng.random_range(0.01..0.3)),
        )
    }

    fn random_point(rng: &mut ChaCha8Rng, spread: f64) -> [f64; 3] {
        [0; 3].map(|_| rng.random_range(-spread..spread))
    }

    /// Distance from `p` to the box by the closest point (clamp in the box frame).
    fn point_distance(p: &Vector3<f64>, c: &Cuboid) -> f64 {
        let local = c.pose.inverse_transform_point(&Point3::from(*p)).coords;
        c.local_point_distance_squared(&local).sqrt()
    }

    /// The twelve edges of a box in the common frame.
    fn edges(c: &Cuboid) -> Vec<([f64; 3], [f64; 3])> {
        let h = Vector3::from(c.half_extents);
        let corner =
            |s: [f64; 3]| (c.pose * Point3::from(h.component_mul(&Vector3::from(s)))).coords;
        let sign = |bit: bool| if bit { 1.0 } else { -1.0 };
        (0..12)
            .map(|e| {
                let (k, mut s0) = (e / 4, [0.0; 3]);
                (s0[(k + 1) % 3], s0[(k + 2) % 3]) = (sign(e & 1 == 1), sign(e & 2 == 2));
                let mut s1 = s0;
                (s0[k], s1[k]) = (-1.0, 1.0);
                (corner(s0).into(), corner(s1).into())
            })
            .collect()
    }

    /// Distance between two boxes: one of the closest points always lies on an edge.
    fn brute_box_distance(a: &Cuboid, b: &Cuboid) -> f64 {
        let ab = edges(a)
            .into_iter()
            .map(|(p, q)| segment_box_distance(p, q, b));
        let ba = edges(b)
            .into_iter()
            .map(|(p, q)| segment_box_distance(p, q, a));
        ab.chain(ba).fold(f64::INFINITY, f64::min)
    }

    /// Unit directions spread over the sphere (Fibonacci lattice).
    fn directions(n: usize) -> Vec<Vector3<f64>> {
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        (0..n)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let r = (1.0 - z * z).sqrt();
                let phi = golden * i as f64;
                Vector3::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect()
    }

    /// Penetration depth by brute force: over many directions, the translation (bisection) after
    /// which `apart(shift)` holds; the minimum over directions.
    fn brute_depth(apart: impl Fn(Vector3<f64>) -> bool, n: usize, reach: f64) -> f64 {
        let mut best = f64::INFINITY;
        for u in directions(n) {
            let (mut lo, mut hi) = (0.0, reach);
            if lo >= best || apart(u * lo) {
                continue;
            }
            hi = f64::min(hi, best);
            if !apart(u * hi) {
                continue;
            }
            for _ in 0..30 {
                let mid = 0.5 * (lo + hi);
                if apart(u * mid) { hi = mid } else { lo = mid }
            }
            best = best.min(hi);
        }
        best
    }

    #[test]
    fn segment_box_distance_is_the_minimum_over_points_of_the_segment() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let (mut touching, mut apart) = (0, 0);
        for _ in 0..300 {
            let c = random_box(&mut rng, 0.2);
            let (a, b) = (random_point(&mut rng, 0.6), random_point(&mut rng, 0.6));
            let exact = segment_box_distance(a, b, &c);
            let (va, vb) = (Vector3::from(a), Vector3::from(b));
            let sampled = (0..=4000)
                .map(|i| point_distance(&(va + (vb - va) * (i as f64 / 4000.0)), &c))
                .fold(f64::INFINITY, f64::min);
            let step = (vb - va).norm() / 4000.0;
            assert!(exact <= sampled + 1e-12, "{exact} > {sampled}");
            assert!(sampled - exact <= step, "{exact} ≪ {sampled}");
            if exact == 0.0 {
                touching += 1
            } else {
                apart += 1
            }
        }
        assert!(
            touching > 30 && apart > 30,
            "{touching} touching, {apart} apart"
        );
    }

    #[test]
    fn segment_box_penetration_is_the_shortest_translation_out() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut checked = 0;
        for _ in 0..40 {
            let c = random_box(&mut rng, 0.1);
            let (a, b) = (random_point(&mut rng, 0.3), random_point(&mut rng, 0.3));
            let depth = segment_box_penetration(a, b, &c);
            let apart = |s: Vector3<f64>| {
                let (p, q) = (Vector3::from(a) + s, Vector3::from(b) + s);
                segment_box_distance(p.into(), q.into(), &c) > 0.0
            };
            if depth == 0.0 {
                assert!(apart(Vector3::zeros()) || segment_box_distance(a, b, &c) == 0.0);
                continue;
            }
            let brute = brute_depth(apart, 1500, 2.0);
            assert!(depth <= brute + 1e-9, "{depth} > brute {brute}");
            assert!(
                brute - depth < 0.01 * brute + 1e-4,
                "{depth} ≪ brute {brute}"
            );
            assert!(segment_box_signed_distance(a, b, &c) == -depth);
            checked += 1;
        }
        assert!(checked >= 10, "only {checked} penetrating segments");
    }

    #[test]
    fn box_box_separation_bounds_the_distance_and_agrees_on_overlap() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (mut overlapping, mut apart, mut exact_gaps) = (0, 0, 0);
        for _ in 0..400 {
            let (a, b) = (random_box(&mut rng, 0.3), random_box(&mut rng, 0.3));
            let separation = box_box_separation(&a, &b);
            let distance = brute_box_distance(&a, &b);
            assert_eq!(
                separation > 1e-12,
                distance > 1e-12,
                "{separation} vs {distance}"
            );
            if distance > 1e-12 {
                assert!(
                    separation <= distance + 1e-12,
                    "{separation} above {distance}"
                );
                exact_gaps += usize::from(distance - separation < 1e-9);
                apart += 1;
            } else {
                overlapping += 1;
            }
        }
        assert!(
            overlapping > 40 && apart > 40,
            "{overlapping} overlap, {apart} apart"
        );
        // A face normal separates most pairs, and there the bound is the distance itself.
        assert!(
            exact_gaps * 3 > apart,
            "the bound is exact for only {exact_gaps}/{apart}"
        );
    }

    #[test]
    fn box_box_penetration_is_the_shortest_translation_out() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut checked = 0;
        while checked < 8 {
            let (a, b) = (random_box(&mut rng, 0.15), random_box(&mut rng, 0.15));
            let Some(depth) = box_box_penetration(&a, &b) else {
                continue;
            };
            let apart = |s: Vector3<f64>| {
                let moved = Cuboid::new(Translation3::from(s) * b.pose, b.half_extents);
                brute_box_distance(&a, &moved) > 0.0
            };
            let brute = brute_depth(apart, 600, 2.0);
            assert!(depth <= brute + 1e-9, "{depth} > brute {brute}");
            assert!(
                brute - depth < 0.03 * brute + 1e-4,
                "{depth} ≪ brute {brute}"
            );
            checked += 1;
        }
    }

    #[test]
    fn parallel_boxes_skip_vanishing_edge_axes() {
        let a = Cuboid::new(Isometry3::identity(), [0.1, 0.1, 0.1]);
        let b = Cuboid::new(Isometry3::translation(0.15, 0.0, 0.0), [0.1, 0.1, 0.1]);
        assert!((box_box_penetration(&a, &b).unwrap_or(0.0) - 0.05).abs() < 1e-12);
        let c = Cuboid::new(Isometry3::translation(0.0, 0.3, 0.0), [0.1, 0.1, 0.1]);
        assert!((box_box_separation(&a, &c) - 0.1).abs() < 1e-12);
    }
}
