//! What bounds a generated body on this machine: how many floating-point
//! multiplications and additions the processor starts per cycle, and
//! whether they share pipes.
//!
//! The generated bodies are long straight-line code, bound by throughput
//! (`docs/performance.md`, "What bounds the bodies"). On cores whose two floating-point pipes do
//! both multiplications and additions (Intel's), a body takes at least
//! `FP ops / 2` cycles (`dynagen ops`, column "FP ops"); on cores with two
//! multiply pipes and two separate adders (AMD Zen 4 and 5), at least
//! `multiplies / 2` (column "multiplies"), however many additions it has.
//! This example measures which, with independent chains of `mulsd` and
//! `addsd` in inline assembly (so the compiler cannot change them), and the
//! clock by a chain of dependent integer additions (one a cycle on every
//! x86-64 core).
//!
//! `cargo run --release -p dynagen-bench --example fp_ports`

#[cfg(target_arch = "x86_64")]
mod x86 {
    use std::arch::asm;
    use std::time::Instant;

    const ITERATIONS: u64 = 50_000_000;

    /// Nanoseconds per iteration of `f`, the best of five runs.
    fn best(f: impl Fn(u64)) -> f64 {
        (0..5)
            .map(|_| {
                let t = Instant::now();
                f(ITERATIONS);
                t.elapsed().as_secs_f64() * 1e9 / ITERATIONS as f64
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// 16 dependent integer additions a pass: 16 cycles.
    fn clock(n: u64) {
        for _ in 0..n {
            // SAFETY: register arithmetic only.
            unsafe {
                asm!(
                    "add {0}, 1", "add {0}, 1", "add {0}, 1", "add {0}, 1",
                    "add {0}, 1", "add {0}, 1", "add {0}, 1", "add {0}, 1",
                    "add {0}, 1", "add {0}, 1", "add {0}, 1", "add {0}, 1",
                    "add {0}, 1", "add {0}, 1", "add {0}, 1", "add {0}, 1",
                    out(reg) _,
                )
            };
        }
    }

    /// 16 multiplications a pass, on 8 independent chains (two deep).
    fn muls(n: u64) {
        for _ in 0..n {
            // SAFETY: register arithmetic only.
            unsafe {
                asm!(
                    "mulsd xmm0, xmm15", "mulsd xmm1, xmm15", "mulsd xmm2, xmm15", "mulsd xmm3, xmm15",
                    "mulsd xmm4, xmm15", "mulsd xmm5, xmm15", "mulsd xmm6, xmm15", "mulsd xmm7, xmm15",
                    "mulsd xmm0, xmm15", "mulsd xmm1, xmm15", "mulsd xmm2, xmm15", "mulsd xmm3, xmm15",
                    "mulsd xmm4, xmm15", "mulsd xmm5, xmm15", "mulsd xmm6, xmm15", "mulsd xmm7, xmm15",
                    out("xmm0") _, out("xmm1") _, out("xmm2") _, out("xmm3") _,
                    out("xmm4") _, out("xmm5") _, out("xmm6") _, out("xmm7") _, out("xmm15") _,
                )
            };
        }
    }

    /// 14 additions a pass, on 7 independent chains (two deep).
    fn adds(n: u64) {
        for _ in 0..n {
            // SAFETY: register arithmetic only.
            unsafe {
                asm!(
                    "addsd xmm8, xmm15", "addsd xmm9, xmm15", "addsd xmm10, xmm15", "addsd xmm11, xmm15",
                    "addsd xmm12, xmm15", "addsd xmm13, xmm15", "addsd xmm14, xmm15",
                    "addsd xmm8, xmm15", "addsd xmm9, xmm15", "addsd xmm10, xmm15", "addsd xmm11, xmm15",
                    "addsd xmm12, xmm15", "addsd xmm13, xmm15", "addsd xmm14, xmm15",
                    out("xmm8") _, out("xmm9") _, out("xmm10") _, out("xmm11") _,
                    out("xmm12") _, out("xmm13") _, out("xmm14") _, out("xmm15") _,
                )
            };
        }
    }

    /// Both passes' instructions in one, interleaved.
    fn mixed(n: u64) {
        for _ in 0..n {
            // SAFETY: register arithmetic only.
            unsafe {
                asm!(
                    "mulsd xmm0, xmm15", "addsd xmm8, xmm15", "mulsd xmm1, xmm15", "addsd xmm9, xmm15",
                    "mulsd xmm2, xmm15", "addsd xmm10, xmm15", "mulsd xmm3, xmm15", "addsd xmm11, xmm15",
                    "mulsd xmm4, xmm15", "addsd xmm12, xmm15", "mulsd xmm5, xmm15", "addsd xmm13, xmm15",
                    "mulsd xmm6, xmm15", "addsd xmm14, xmm15", "mulsd xmm7, xmm15",
                    "mulsd xmm0, xmm15", "addsd xmm8, xmm15", "mulsd xmm1, xmm15", "addsd xmm9, xmm15",
                    "mulsd xmm2, xmm15", "addsd xmm10, xmm15", "mulsd xmm3, xmm15", "addsd xmm11, xmm15",
                    "mulsd xmm4, xmm15", "addsd xmm12, xmm15", "mulsd xmm5, xmm15", "addsd xmm13, xmm15",
                    "mulsd xmm6, xmm15", "addsd xmm14, xmm15", "mulsd xmm7, xmm15",
                    out("xmm0") _, out("xmm1") _, out("xmm2") _, out("xmm3") _,
                    out("xmm4") _, out("xmm5") _, out("xmm6") _, out("xmm7") _,
                    out("xmm8") _, out("xmm9") _, out("xmm10") _, out("xmm11") _,
                    out("xmm12") _, out("xmm13") _, out("xmm14") _, out("xmm15") _,
                )
            };
        }
    }

    pub fn main() {
        let cycle = best(clock) / 16.0;
        let cycles = |ns: f64| ns / cycle;
        let (m, a, both) = (cycles(best(muls)), cycles(best(adds)), cycles(best(mixed)));
        println!("clock: {:.2} GHz (dependent integer additions)", 1.0 / cycle);
        println!("16 multiplications: {m:.1} cycles, {:.2} a cycle", 16.0 / m);
        println!("14 additions: {a:.1} cycles, {:.2} a cycle", 14.0 / a);
        println!(
            "both, interleaved: {both:.1} cycles (separate pipes: about {:.1}; shared: about {:.1})",
            m.max(a),
            m + a
        );
        let separate = both < 0.75 * (m + a);
        if separate {
            println!(
                "multiplications and additions run on separate pipes: a body takes at least \
                 `multiplies` / {:.1} cycles (`dynagen ops`)",
                16.0 / m
            );
        } else {
            println!(
                "multiplications and additions share pipes: a body takes at least `FP ops` / {:.1} cycles \
                 (`dynagen ops`)",
                16.0 / m
            );
        }
    }
}

fn main() {
    #[cfg(target_arch = "x86_64")]
    x86::main();
    #[cfg(not(target_arch = "x86_64"))]
    println!("fp_ports measures x86-64 processors only");
}
