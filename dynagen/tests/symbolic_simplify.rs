//! The symbolic expression graph (`dynagen::symbolic`): its simplification
//! rules, one by one, and the trace session's guarantees.

use dynagen::symbolic::{Expr, Graph, Node, Rewrites, TraceActive, Traced, Tracer};
use dynagen::Scalar;

fn xy(g: &mut Graph) -> (u32, u32) {
    (g.input("q", 0), g.input("q", 1))
}

#[test]
fn constants_fold() {
    let mut g = Graph::new();
    let (a, b) = (g.constant(2.0), g.constant(3.0));
    let cases = [(g.add(a, b), 5.0), (g.sub(a, b), -1.0), (g.mul(a, b), 6.0), (g.div(a, b), 2.0 / 3.0)];
    for (id, want) in cases {
        assert_eq!(g.constant_value(id), Some(want));
    }
    let n = g.neg(a);
    assert_eq!(g.constant_value(n), Some(-2.0));
    let r = g.sqrt(a);
    assert_eq!(g.constant_value(r), Some(2f64.sqrt()));
    let (s, c) = g.sin_cos(a);
    assert_eq!((g.constant_value(s), g.constant_value(c)), (Some(2f64.sin()), Some(2f64.cos())));
    assert!(g.nodes().iter().all(|n| n.constant().is_some()));
}

#[test]
fn identities_simplify_as_built() {
    let mut g = Graph::new();
    let (x, _) = xy(&mut g);
    let (zero, one, m1) = (g.constant(0.0), g.constant(1.0), g.constant(-1.0));
    let before = g.len();
    assert_eq!(g.mul(zero, x), zero, "0·x");
    assert_eq!(g.mul(x, zero), zero, "x·0");
    assert_eq!(g.mul(one, x), x, "1·x");
    assert_eq!(g.mul(x, one), x, "x·1");
    assert_eq!(g.add(x, zero), x, "x + 0");
    assert_eq!(g.add(zero, x), x, "0 + x");
    assert_eq!(g.sub(x, zero), x, "x − 0");
    assert_eq!(g.sub(x, x), zero, "x − x");
    assert_eq!(g.div(x, one), x, "x / 1");
    assert_eq!(g.div(zero, x), zero, "0 / x");
    assert_eq!(g.div(x, x), one, "x / x");
    assert_eq!(g.len(), before, "no node was built");
    let nx = g.neg(x);
    assert_eq!(g.node(nx), Node::Neg(x));
    assert_eq!(g.neg(nx), x, "−(−x)");
    assert_eq!(g.mul(x, m1), nx, "x·(−1)");
    assert_eq!(g.div(x, m1), nx, "x / −1");
    assert_eq!(g.sub(zero, x), nx, "0 − x");
}

#[test]
fn negations_move_outwards_and_meet_additions() {
    let mut g = Graph::new();
    let (x, y) = xy(&mut g);
    let (nx, ny) = (g.neg(x), g.neg(y));
    let diff = g.sub(x, y);
    assert_eq!(g.add(x, ny), diff, "x + (−y) = x − y");
    let sum = g.add(x, y);
    assert_eq!(g.sub(x, ny), sum, "x − (−y) = x + y");
    let xy_ = g.mul(x, y);
    assert_eq!(g.mul(nx, ny), xy_, "(−x)(−y) = xy");
    let nxy = g.neg(xy_);
    assert_eq!(g.mul(nx, y), nxy, "(−x)y = −(xy)");
    assert_eq!(g.mul(x, ny), nxy, "x(−y) = −(xy)");
    let yx = g.sub(y, x);
    assert_eq!(g.neg(diff), yx, "−(x − y) = y − x");
    let (c2, cm2) = (g.constant(2.0), g.constant(-2.0));
    let two_x = g.mul(c2, x);
    let m = g.mul(cm2, x);
    assert_eq!(g.node(m), Node::Neg(two_x), "−2x shares 2x");
    let x_minus_2 = g.sub(x, c2);
    assert_eq!(g.add(x, cm2), x_minus_2, "x + (−2) = x − 2");
    // sin(−x) = −sin x, cos(−x) = cos x
    let (s, c) = g.sin_cos(x);
    let (sn, cn) = g.sin_cos(nx);
    assert_eq!((g.node(sn), cn), (Node::Neg(s), c));
}

#[test]
fn exact_algebraic_cancellations() {
    let mut g = Graph::new();
    let (x, y) = xy(&mut g);
    let one = g.constant(1.0);
    let sum = g.add(x, y);
    assert_eq!(g.sub(sum, y), x, "(x + y) − y");
    assert_eq!(g.sub(sum, x), y, "(x + y) − x");
    // Rodrigues on a joint's own axis: c + (1 − c) = 1
    let t = g.sub(one, x);
    assert_eq!(g.add(x, t), one, "x + (1 − x)");
    assert_eq!(g.add(t, x), one, "(1 − x) + x");
    let d = g.sub(x, y);
    assert_eq!(g.sub(x, d), y, "x − (x − y)");
    let ny = g.neg(y);
    assert_eq!(g.sub(d, x), ny, "(x − y) − x");
}

#[test]
fn commutative_operands_meet_and_nodes_are_shared() {
    let mut g = Graph::new();
    let (x, y) = xy(&mut g);
    assert_eq!(g.add(x, y), g.add(y, x));
    assert_eq!(g.mul(x, y), g.mul(y, x));
    let c = g.constant(3.5);
    assert_eq!(g.mul(x, c), g.mul(c, x));
    let n = g.len();
    let a = g.mul(x, y);
    let b = g.add(a, c);
    let b2 = {
        let a2 = g.mul(y, x);
        g.add(c, a2)
    };
    assert_eq!(b, b2);
    assert_eq!(g.len(), n + 1, "only x·y + 3.5 was new");
    assert_ne!(g.sub(x, y), g.sub(y, x), "subtraction keeps its order");
    // sine and cosine of one angle share one node
    let (s, c) = g.sin_cos(x);
    let (s2, c2) = g.sin_cos(x);
    assert_eq!((s, c), (s2, c2));
    assert_eq!(g.nodes().iter().filter(|n| matches!(n, Node::SinCos(_))).count(), 1);
}

#[test]
fn value_changing_rewrites_follow_the_options() {
    for (rewrites, combined) in [(Rewrites::default(), true), (Rewrites::exact(), false)] {
        let mut g = Graph::with_rewrites(rewrites);
        let (x, _) = xy(&mut g);
        let (a, b) = (g.constant(0.1), g.constant(0.2));
        let (ax, bx) = (g.mul(a, x), g.mul(b, x));
        let s = g.add(ax, bx);
        let ab = g.mul(a, bx);
        let xa = g.add(x, a);
        let xab = g.add(xa, b);
        let xa_b = g.sub(xa, b);
        if combined {
            let c = g.constant(0.1 + 0.2);
            assert_eq!(g.node(xab), Node::Add(x, c), "(x + 0.1) + 0.2 = x + 0.30000000000000004");
            let c = g.constant(0.2 - 0.1);
            assert_eq!(g.node(xa_b), Node::Sub(x, c), "(x + 0.1) − 0.2 = x − 0.1");
        } else {
            assert_eq!(g.node(xab), Node::Add(b.min(xa), b.max(xa)));
        }
        if combined {
            let c = g.constant(0.1 + 0.2);
            assert_eq!(g.node(s), Node::Mul(c, x), "0.1x + 0.2x = 0.30000000000000004x");
            let c = g.constant(0.1 * 0.2);
            assert_eq!(g.node(ab), Node::Mul(c, x), "0.1(0.2x) = 0.020000000000000004x");
        } else {
            assert_eq!(g.node(s), Node::Add(ax, bx));
            assert_eq!(g.node(ab), Node::Mul(a, bx));
        }
    }
}

#[test]
fn division_by_a_power_of_two_is_a_multiplication() {
    let mut g = Graph::new();
    let (x, _) = xy(&mut g);
    let four = g.constant(4.0);
    let q = g.div(x, four);
    let quarter = g.constant(0.25);
    assert_eq!(g.node(q), Node::Mul(quarter, x));
    let three = g.constant(3.0);
    let q3 = g.div(x, three);
    assert_eq!(g.node(q3), Node::Div(x, three), "x/3 stays a division (1/3 is inexact)");
}

#[test]
fn dead_code_is_eliminated_and_counted() {
    let mut g = Graph::new();
    let (x, y) = xy(&mut g);
    let dead = g.mul(x, y);
    let _ = g.sqrt(dead);
    let (s, c) = g.sin_cos(x);
    let sc = g.mul(s, c);
    let out = g.add(sc, y);
    let f = Traced::from_ids("f", &g, &[out, s]);
    let count = f.op_count();
    assert_eq!((count.add, count.mul, count.sqrt, count.sin_cos, count.total()), (1, 1, 0, 1, 3));
    // q0, q1, sin_cos, sin, cos, s·c, s·c + q1
    assert_eq!(f.nodes().len(), 7);
    let v = f.eval(&[("q", &[0.3, -2.0])]).unwrap();
    assert_eq!(v, vec![0.3f64.sin() * 0.3f64.cos() + -2.0, 0.3f64.sin()]);
    assert!(f.eval(&[("q", &[0.3])]).is_err(), "q[1] missing");
}

#[test]
fn tracer_sessions_are_per_thread_and_do_not_leak() {
    let t = Tracer::start().unwrap();
    assert_eq!(Tracer::start().unwrap_err(), TraceActive);
    let x = t.input("q", 0);
    let y = (x * Expr::from_f64(2.0)).sin() + Expr::one();
    let g = t.finish();
    let f = Traced::new("f", &g, &[y]);
    assert_eq!(f.eval(&[("q", &[0.5])]).unwrap(), vec![1.0f64.sin() + 1.0]);
    // A new session starts empty.
    let t2 = Tracer::start().unwrap();
    assert_eq!(t2.finish().len(), 0);
    // Two threads trace at once, independently.
    let h: Vec<_> = (0..2)
        .map(|k| {
            std::thread::spawn(move || {
                let t = Tracer::start().unwrap();
                let x = t.input("q", 0);
                let mut acc = x;
                for i in 0..1000 {
                    acc = acc * x + Expr::from_f64((i + k) as f64);
                }
                let g = t.finish();
                Traced::new("f", &g, &[acc]).eval(&[("q", &[0.5])]).unwrap()[0]
            })
        })
        .collect();
    let r: Vec<f64> = h.into_iter().map(|h| h.join().unwrap()).collect();
    for (k, got) in r.iter().enumerate() {
        let want = (0..1000).fold(0.5, |acc: f64, i| acc * 0.5 + (i + k) as f64);
        assert_eq!(*got, want);
    }
}

#[test]
#[should_panic(expected = "outside the Tracer session")]
fn an_expression_from_a_finished_trace_is_refused() {
    let t = Tracer::start().unwrap();
    let x = t.input("q", 0);
    drop(t.finish());
    let _t2 = Tracer::start().unwrap();
    let _ = x + x;
}

#[test]
fn factoring_after_the_trace_uses_use_counts() {
    use dynagen::symbolic::factor;
    let mut g = Graph::new();
    let (x, y) = xy(&mut g);
    let k = g.input("k", 0);
    let (kx, ky) = (g.mul(k, x), g.mul(k, y));
    let s = g.add(kx, ky);
    // k·x + k·y, each product used once: k·(x + y), one multiplication fewer
    let f = Traced::from_ids("f", &g, &[s]);
    let ff = factor(&f, Rewrites::default());
    assert_eq!((f.op_count().mul, ff.op_count().mul), (2, 1));
    let args: [(&str, &[f64]); 2] = [("q", &[0.25, 0.5]), ("k", &[3.0])];
    assert_eq!(ff.eval(&args).unwrap(), vec![3.0 * (0.25 + 0.5)]);
    // k·x is also an output: sharing would cost one more, nothing changes
    let f2 = Traced::from_ids("f", &g, &[s, kx]);
    assert_eq!(factor(&f2, Rewrites::default()).op_count(), f2.op_count());
    // (−x) − y → −(x + y), whose negation the next subtraction absorbs
    let nx = g.neg(x);
    let d = g.sub(nx, y);
    let e = g.sub(k, d);
    let f3 = Traced::from_ids("f", &g, &[e]);
    let f3f = factor(&f3, Rewrites::default());
    assert_eq!((f3.op_count().total(), f3f.op_count().total()), (3, 2));
    assert_eq!(f3f.eval(&args).unwrap(), vec![3.0 + (0.25 + 0.5)]);
    // off with exact rewrites
    assert_eq!(factor(&f, Rewrites::exact()), f);
}
