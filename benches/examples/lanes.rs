//! An experiment for issue 17 (not a product): how fast the floating
//! quadruped12's mass matrix gets when its four legs are computed in the
//! four lanes of one AVX2 vector, each lane a leg and each of the leg's
//! constants a vector of the four legs' values.
//!
//! The four legs of the quadruped have the same joints (axes x, y, y) and
//! placements that differ only in their constants, so one leg's composite
//! inertia algorithm computes all four at once. This is the hand-written
//! form of what code generation would emit for isomorphic branches; it is
//! checked against the generated `mass_matrix` (≤ 1e-12) and timed against
//! it, alternately, as `examples/floating.rs` times (8 states, the minimum
//! per call over rounds of 2000 calls). Both take the same sines and
//! cosines for the body, and each its own for the whole call. The result
//! is in docs/performance.md ("Legs in vector lanes").
//!
//! `cargo run --release -p dynagen-bench --example lanes [ROUNDS]`
//! (x86-64 with AVX2 and FMA only)

#[cfg(target_arch = "x86_64")]
mod lanes {
    use core::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_fmadd_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setr_pd, _mm256_sub_pd,
        _mm256_xor_pd,
    };
    use core::ops::{Add, Mul, Neg, Sub};
    use dynagen::spatial::Inertia;
    use dynagen::Model;

    /// Four lanes: one value per leg.
    #[derive(Clone, Copy)]
    pub struct L(__m256d);

    impl L {
        #[inline(always)]
        fn lanes(self) -> [f64; 4] {
            // SAFETY: __m256d and [f64; 4] have the same size and any bits are valid.
            unsafe { core::mem::transmute::<__m256d, [f64; 4]>(self.0) }
        }
        #[inline(always)]
        fn new(v: [f64; 4]) -> L {
            // SAFETY: AVX is present (checked before any lane is built).
            L(unsafe { _mm256_setr_pd(v[0], v[1], v[2], v[3]) })
        }
    }

    macro_rules! binop {
        ($t:ident, $f:ident, $i:ident) => {
            impl $t for L {
                type Output = L;
                #[inline(always)]
                fn $f(self, o: L) -> L {
                    // SAFETY: AVX is present (checked before any lane is built).
                    L(unsafe { $i(self.0, o.0) })
                }
            }
        };
    }
    binop!(Add, add, _mm256_add_pd);
    binop!(Sub, sub, _mm256_sub_pd);
    binop!(Mul, mul, _mm256_mul_pd);

    impl Neg for L {
        type Output = L;
        #[inline(always)]
        fn neg(self) -> L {
            // SAFETY: AVX is present (checked before any lane is built).
            L(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
        }
    }

    /// `a·b + c`, one rounding.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn fma(a: L, b: L, c: L) -> L {
        L(_mm256_fmadd_pd(a.0, b.0, c.0))
    }

    /// `x` in every lane.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn k(x: f64) -> L {
        L(_mm256_set1_pd(x))
    }

    /// The sum of the four lanes.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn hsum(a: L) -> f64 {
        let v = a.lanes();
        (v[0] + v[1]) + (v[2] + v[3])
    }

    /// A composite rigid-body inertia about a frame's origin: mass, h = m·c
    /// and the rotational inertia (xx, yy, zz, xy, xz, yz).
    #[derive(Clone, Copy)]
    struct Ci {
        m: L,
        h: [L; 3],
        i: [L; 6],
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn add(a: Ci, b: Ci) -> Ci {
        Ci {
            m: a.m + b.m,
            h: [a.h[0] + b.h[0], a.h[1] + b.h[1], a.h[2] + b.h[2]],
            i: core::array::from_fn(|q| a.i[q] + b.i[q]),
        }
    }

    /// The inertia turned about y by (c, s) (cos and sin of the double angle
    /// in c2, s2): a child's in its parent's orientation.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn rot_y(a: Ci, [c, s, c2, s2]: [L; 4]) -> Ci {
        let [hx, hy, hz] = a.h;
        let [ixx, iyy, izz, ixy, ixz, iyz] = a.i;
        let d = (ixx - izz) * k(0.5);
        let mid = (ixx + izz) * k(0.5);
        let dc = fma(d, c2, ixz * s2);
        Ci {
            m: a.m,
            h: [fma(c, hx, s * hz), hy, fma(c, hz, -(s * hx))],
            i: [mid + dc, iyy, mid - dc, fma(c, ixy, s * iyz), fma(ixz, c2, -(d * s2)), fma(c, iyz, -(s * ixy))],
        }
    }

    /// The inertia turned about x.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn rot_x(a: Ci, [c, s, c2, s2]: [L; 4]) -> Ci {
        let [hx, hy, hz] = a.h;
        let [ixx, iyy, izz, ixy, ixz, iyz] = a.i;
        let d = (iyy - izz) * k(0.5);
        let mid = (iyy + izz) * k(0.5);
        let dc = fma(d, c2, -(iyz * s2));
        Ci {
            m: a.m,
            h: [hx, fma(c, hy, -(s * hz)), fma(s, hy, c * hz)],
            i: [ixx, mid + dc, mid - dc, fma(c, ixy, -(s * ixz)), fma(s, ixy, c * ixz), fma(d, s2, iyz * c2)],
        }
    }

    /// The inertia about the origin moved to p = (px, py, pz): I + 2(p·h) 1
    /// − (p hᵀ + h pᵀ) + m(|p|² 1 − p pᵀ), h + m p. A component that is zero
    /// in all four legs is `None` and costs nothing.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn moved(a: Ci, p: [Option<L>; 3]) -> Ci {
        let (m, [hx, hy, hz]) = (a.m, a.h);
        let [ixx, iyy, izz, ixy, ixz, iyz] = a.i;
        // 2 p_k h_k + m p_k², the part of the diagonal from component k.
        let sq = |pk: Option<L>, hk: L| pk.map(|p| fma(k(2.0) * p, hk, m * p * p));
        let (ax, ay, az) = (sq(p[0], hx), sq(p[1], hy), sq(p[2], hz));
        let plus = |x: L, t: Option<L>| t.map_or(x, |t| x + t);
        // −(p_a h_b + p_b h_a + m p_a p_b), the off-diagonal entry (a, b).
        let off = |x: L, pa: Option<L>, ha: L, pb: Option<L>, hb: L| {
            let x = pa.map_or(x, |pa| fma(-pa, hb, x));
            let x = pb.map_or(x, |pb| fma(-pb, ha, x));
            match (pa, pb) {
                (Some(pa), Some(pb)) => fma(-(m * pa), pb, x),
                _ => x,
            }
        };
        Ci {
            m,
            h: [plus(hx, p[0].map(|p| m * p)), plus(hy, p[1].map(|p| m * p)), plus(hz, p[2].map(|p| m * p))],
            i: [
                plus(plus(ixx, ay), az),
                plus(plus(iyy, ax), az),
                plus(plus(izz, ax), ay),
                off(ixy, p[0], hx, p[1], hy),
                off(ixz, p[0], hx, p[2], hz),
                off(iyz, p[1], hy, p[2], hz),
            ],
        }
    }

    /// A spatial force (n; f).
    type F = [L; 6];

    /// A force of a joint's frame in its parent's: turned about the joint's
    /// axis (y or x) by (c, s), then moved by p (n' = R n + p × R f).
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn carried(x: F, about_x: bool, c: L, s: L, p: [Option<L>; 3]) -> F {
        let [nx, ny, nz, fx, fy, fz] = x;
        let turn = |[vx, vy, vz]: [L; 3]| {
            if about_x {
                [vx, fma(c, vy, -(s * vz)), fma(s, vy, c * vz)]
            } else {
                [fma(c, vx, s * vz), vy, fma(c, vz, -(s * vx))]
            }
        };
        let (n, f) = (turn([nx, ny, nz]), turn([fx, fy, fz]));
        // p × f, term by term, skipping the zero components of p.
        let cross = |n: L, pa: Option<L>, fb: L, pb: Option<L>, fa: L| {
            let n = pa.map_or(n, |pa| fma(pa, fb, n));
            pb.map_or(n, |pb| fma(-pb, fa, n))
        };
        [
            cross(n[0], p[1], f[2], p[2], f[1]),
            cross(n[1], p[2], f[0], p[0], f[2]),
            cross(n[2], p[0], f[1], p[1], f[0]),
            f[0],
            f[1],
            f[2],
        ]
    }

    /// The legs' constants, lane by lane.
    pub struct Legs {
        bodies: [Ci; 3],
        placements: [[L; 3]; 3],
        trunk: Inertia<f64>,
    }

    /// Which components of each joint's placement are nonzero in some leg
    /// (hip: x, y; thigh: y; calf: z): the rest cost nothing.
    const NONZERO: [[bool; 3]; 3] = [[true, true, false], [false, true, false], [false, false, true]];

    /// The lanes of the quadruped12's legs (joint order FR, FL, RR, RL, each
    /// hip, thigh, calf), checking that the legs are what the lanes assume:
    /// identity rotations in the placements, axes x, y, y.
    pub fn legs(model: &Model) -> Result<Legs, String> {
        if model.bodies.len() != 12
            || !(0..12).all(|b| model.bodies[b].parent == if b % 3 == 0 { None } else { Some(b - 1) })
        {
            return Err("not four legs of three joints".into());
        }
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let mut bodies = Vec::new();
        let mut placements = Vec::new();
        for j in 0..3 {
            let of = |leg: usize| &model.bodies[3 * leg + j];
            for leg in 0..4 {
                let joint = &of(leg).joint;
                if joint.axis.0 != axes[j]
                    || joint.placement.rot.0 != [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
                {
                    return Err(format!("joint {} is not as the lanes assume", joint.name));
                }
            }
            let lane = |f: &dyn Fn(usize) -> f64| L::new([f(0), f(1), f(2), f(3)]);
            bodies.push(Ci {
                m: lane(&|l| of(l).inertia.mass),
                h: core::array::from_fn(|q| lane(&|l| of(l).inertia.h.0[q])),
                i: core::array::from_fn(|q| lane(&|l| of(l).inertia.ibar.0[q])),
            });
            let p: [[f64; 4]; 3] = core::array::from_fn(|q| [0, 1, 2, 3].map(|l| of(l).joint.placement.trans.0[q]));
            if (0..3).any(|q| !NONZERO[j][q] && p[q] != [0.0; 4]) {
                return Err(format!("joint {} is placed where the lanes assume zeros", of(0).joint.name));
            }
            placements.push(p.map(L::new));
        }
        Ok(Legs {
            bodies: [bodies[0], bodies[1], bodies[2]],
            placements: [placements[0], placements[1], placements[2]],
            trunk: model.base_inertia,
        })
    }

    /// The floating mass matrix (18 × 18, base first) from the joints' sines
    /// and cosines.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn mass_matrix_on(legs: &Legs, s: &[f64; 12], c: &[f64; 12], out: &mut [[f64; 18]; 18]) {
        let trig = |j: usize| {
            let (c, s) = (L::new([c[j], c[3 + j], c[6 + j], c[9 + j]]), L::new([s[j], s[3 + j], s[6 + j], s[9 + j]]));
            [c, s, fma(c, c, -(s * s)), k(2.0) * c * s]
        };
        let (t1, t2, t3) = (trig(0), trig(1), trig(2));
        // The placements with the components that are zero in every leg as None.
        let placement =
            |j: usize| -> [Option<L>; 3] { core::array::from_fn(|q| NONZERO[j][q].then_some(legs.placements[j][q])) };
        let (p1, p2, p3) = (placement(0), placement(1), placement(2));
        // Composite inertias, each in its joint's frame, and the leg's in the trunk's.
        let i3 = legs.bodies[2];
        let i2 = add(legs.bodies[1], moved(rot_y(i3, t3), p3));
        let i1 = add(legs.bodies[0], moved(rot_y(i2, t2), p2));
        let ib = moved(rot_x(i1, t1), p1);
        // The joints' columns F = I·S (axis y: n = I e_y, f = e_y × h; axis
        // x: n = I e_x, f = e_x × h), carried up to the trunk.
        let zero = k(0.0);
        let f3 = [i3.i[3], i3.i[1], i3.i[5], i3.h[2], zero, -i3.h[0]];
        let f3_2 = carried(f3, false, t3[0], t3[1], p3);
        let f3_1 = carried(f3_2, false, t2[0], t2[1], p2);
        let f3_b = carried(f3_1, true, t1[0], t1[1], p1);
        let f2 = [i2.i[3], i2.i[1], i2.i[5], i2.h[2], zero, -i2.h[0]];
        let f2_1 = carried(f2, false, t2[0], t2[1], p2);
        let f2_b = carried(f2_1, true, t1[0], t1[1], p1);
        let f1 = [i1.i[0], i1.i[3], i1.i[4], zero, -i1.h[2], i1.h[1]];
        let f1_b = carried(f1, true, t1[0], t1[1], p1);
        // The trunk's block: its own inertia plus the four legs'.
        let t = &legs.trunk;
        let h: [f64; 3] = core::array::from_fn(|q| t.h.0[q] + hsum(ib.h[q]));
        let [ixx, iyy, izz, ixy, ixz, iyz]: [f64; 6] = core::array::from_fn(|q| t.ibar.0[q] + hsum(ib.i[q]));
        let m = t.mass + hsum(ib.m);
        let (d, a12, a13, a23) =
            ([i1.i[0], i2.i[1], i3.i[1]].map(L::lanes), f2_1[0].lanes(), f3_1[0].lanes(), f3_2[1].lanes());
        let columns = [f1_b.map(L::lanes), f2_b.map(L::lanes), f3_b.map(L::lanes)];
        let base_row = |r: usize, base: [f64; 6]| {
            let mut row = [0.0; 18];
            row[..6].copy_from_slice(&base);
            for l in 0..4 {
                for (j, col) in columns.iter().enumerate() {
                    row[6 + 3 * l + j] = col[r][l];
                }
            }
            row
        };
        let joint_row = |l: usize, j: usize| {
            let mut row = [0.0; 18];
            for (r, x) in row[..6].iter_mut().enumerate() {
                *x = columns[j][r][l];
            }
            let leg = [[d[0][l], a12[l], a13[l]], [a12[l], d[1][l], a23[l]], [a13[l], a23[l], d[2][l]]];
            row[6 + 3 * l..9 + 3 * l].copy_from_slice(&leg[j]);
            row
        };
        *out = [
            base_row(0, [ixx, ixy, ixz, 0.0, -h[2], h[1]]),
            base_row(1, [ixy, iyy, iyz, h[2], 0.0, -h[0]]),
            base_row(2, [ixz, iyz, izz, -h[1], h[0], 0.0]),
            base_row(3, [0.0, h[2], -h[1], m, 0.0, 0.0]),
            base_row(4, [-h[2], 0.0, h[0], 0.0, m, 0.0]),
            base_row(5, [h[1], -h[0], 0.0, 0.0, 0.0, m]),
            joint_row(0, 0),
            joint_row(0, 1),
            joint_row(0, 2),
            joint_row(1, 0),
            joint_row(1, 1),
            joint_row(1, 2),
            joint_row(2, 0),
            joint_row(2, 1),
            joint_row(2, 2),
            joint_row(3, 0),
            joint_row(3, 1),
            joint_row(3, 2),
        ];
    }

    #[target_feature(enable = "avx2,fma")]
    unsafe fn mass_matrix_avx2_fma(legs: &Legs, s: &[f64; 12], c: &[f64; 12], out: &mut [[f64; 18]; 18]) {
        mass_matrix_on(legs, s, c, out)
    }

    /// The mass matrix into `out`. Panics without AVX2 and FMA.
    pub fn mass_matrix(legs: &Legs, s: &[f64; 12], c: &[f64; 12], out: &mut [[f64; 18]; 18]) {
        assert!(is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma"), "needs AVX2 and FMA");
        // SAFETY: both features were checked just above.
        unsafe { mass_matrix_avx2_fma(legs, s, c, out) }
    }
}

#[cfg(target_arch = "x86_64")]
fn main() {
    use dynagen_bench::quadruped12_floating as generated;
    use std::hint::black_box;
    use std::time::Instant;

    if !(is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")) {
        println!("this processor has no AVX2 and FMA: nothing to time");
        return;
    }
    let rounds: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(200);
    let urdf = concat!(env!("CARGO_MANIFEST_DIR"), "/../dynagen/robots/quadruped12.urdf");
    let model = dynagen::Model::from_urdf_file(urdf).expect("quadruped12.urdf").with_floating_base();
    let legs = lanes::legs(&model).expect("the quadruped's legs");
    // 8 states as examples/floating.rs draws them (the base does not enter M).
    let mut next = dynagen_bench::uniform(0x5eed);
    let qs: Vec<[f64; 19]> = (0..8)
        .map(|_| {
            let mut q = [0.0; 19];
            q[6] = 1.0;
            for j in &mut q[7..] {
                *j = std::f64::consts::PI * next();
            }
            q
        })
        .collect();
    let trig: Vec<([f64; 12], [f64; 12])> =
        qs.iter().map(|q| generated::sin_cos_all(&core::array::from_fn(|i| q[7 + i]))).collect();
    let mut out = Box::new([[0.0; 18]; 18]);
    for (q, (s, c)) in qs.iter().zip(&trig) {
        let m = generated::mass_matrix(q);
        lanes::mass_matrix(&legs, s, c, &mut out);
        let scale = m.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        for (a, b) in m.iter().flatten().zip(out.iter().flatten()) {
            assert!((a - b).abs() <= 1e-12 * scale, "lanes {b} against generated {a}");
        }
    }
    // Body (sines and cosines given) and whole call, alternately.
    type Timed<'a> = (&'a str, &'a dyn Fn(usize, &mut [[f64; 18]; 18]));
    let bodies: [Timed; 4] = [
        // The generated functions return M: it stays where they write it.
        ("generated body (mass_matrix_sc)", &|i, _| {
            black_box(&generated::mass_matrix_sc(&trig[i].0, &trig[i].1, &qs[i]));
        }),
        ("lanes body", &|i, out| lanes::mass_matrix(&legs, &trig[i].0, &trig[i].1, out)),
        ("generated mass_matrix(q)", &|i, _| {
            black_box(&generated::mass_matrix(&qs[i]));
        }),
        ("lanes + sin_cos_all", &|i, out| {
            let (s, c) = generated::sin_cos_all(&core::array::from_fn(|k| qs[i][7 + k]));
            lanes::mass_matrix(&legs, &s, &c, out)
        }),
    ];
    let mut times = vec![Vec::with_capacity(rounds); bodies.len()];
    for r in 0..rounds {
        for j in 0..bodies.len() {
            let k = if r % 2 == 0 { j } else { bodies.len() - 1 - j };
            let t = Instant::now();
            for i in 0..2000 {
                bodies[k].1(black_box(i & 7), &mut out);
                black_box(&mut out);
            }
            times[k].push(t.elapsed().as_nanos() as f64 / 2000.0);
        }
    }
    println!("quadruped12 floating M, legs in four lanes against generated, {rounds} rounds of 2000 calls");
    for ((name, _), t) in bodies.iter().zip(&mut times) {
        t.sort_by(f64::total_cmp);
        println!("{name:<32} min {:7.1} ns  median {:7.1} ns", t[0], t[t.len() / 2]);
    }
}

#[cfg(not(target_arch = "x86_64"))]
fn main() {
    println!("x86-64 only");
}
