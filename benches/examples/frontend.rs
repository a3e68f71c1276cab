//! How fast this processor runs straight-line code, by the length of the
//! code: what bounds a generated body too long for the core's micro-op
//! cache (`docs/performance.md`, "What bounds the bodies").
//!
//! A generated body runs once per call, start to end, without loops. While
//! its instructions fit in the micro-op cache, the core takes them from
//! there, six or more a cycle. Beyond it they go through the legacy
//! decoders, which take a fixed number of *bytes* a cycle: time then grows
//! with the body's size in bytes, not with its arithmetic. This example
//! times functions of independent integer additions (so that nothing but
//! the front end limits them) of 1,000 to 12,000 instructions, 4 and 7
//! bytes long, and prints ns per instruction and bytes per ns. Compare the
//! sizes of generated bodies (`nm -S --size-sort` on a binary that links
//! them) with the cliff it finds.
//!
//! `cargo run --release -p dynagen-bench --example frontend`

#[cfg(target_arch = "x86_64")]
mod x86 {
    use std::time::Instant;

    /// A function of `8 × $reps` additions on eight registers: `$add` is
    /// `1` (4-byte instructions) or `0x1234567` (7-byte instructions).
    macro_rules! straight {
        ($name:ident, $reps:literal, $add:literal) => {
            #[inline(never)]
            fn $name() {
                // SAFETY: register arithmetic only, on registers declared clobbered.
                unsafe {
                    std::arch::asm!(
                        concat!(".rept ", $reps),
                        concat!("add r8, ", $add),
                        concat!("add r9, ", $add),
                        concat!("add r10, ", $add),
                        concat!("add r11, ", $add),
                        concat!("add rax, ", $add),
                        concat!("add rcx, ", $add),
                        concat!("add rdx, ", $add),
                        concat!("add rsi, ", $add),
                        ".endr",
                        out("r8") _, out("r9") _, out("r10") _, out("r11") _,
                        out("rax") _, out("rcx") _, out("rdx") _, out("rsi") _,
                    )
                }
            }
        };
    }

    straight!(short_1000, 125, 1);
    straight!(short_2000, 250, 1);
    straight!(short_3000, 375, 1);
    straight!(short_4000, 500, 1);
    straight!(short_5000, 625, 1);
    straight!(short_6000, 750, 1);
    straight!(short_8000, 1000, 1);
    straight!(short_12000, 1500, 1);
    straight!(long_1000, 125, 0x1234567);
    straight!(long_2000, 250, 0x1234567);
    straight!(long_3000, 375, 0x1234567);
    straight!(long_4000, 500, 0x1234567);
    straight!(long_5000, 625, 0x1234567);
    straight!(long_6000, 750, 0x1234567);
    straight!(long_8000, 1000, 0x1234567);
    straight!(long_12000, 1500, 0x1234567);

    /// Nanoseconds per call of `f`: the best of 200 rounds of 200 calls.
    fn best(f: fn()) -> f64 {
        (0..200)
            .map(|_| {
                let t = Instant::now();
                for _ in 0..200 {
                    f();
                }
                t.elapsed().as_secs_f64() * 1e9 / 200.0
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// A set of functions of one instruction length: its name, the length in
    /// bytes, and each function with its number of instructions.
    type Set = (&'static str, usize, [(usize, fn()); 8]);

    pub fn main() {
        let sets: [Set; 2] = [
            (
                "4-byte",
                4,
                [
                    (1000, short_1000),
                    (2000, short_2000),
                    (3000, short_3000),
                    (4000, short_4000),
                    (5000, short_5000),
                    (6000, short_6000),
                    (8000, short_8000),
                    (12000, short_12000),
                ],
            ),
            (
                "7-byte",
                7,
                [
                    (1000, long_1000),
                    (2000, long_2000),
                    (3000, long_3000),
                    (4000, long_4000),
                    (5000, long_5000),
                    (6000, long_6000),
                    (8000, long_8000),
                    (12000, long_12000),
                ],
            ),
        ];
        println!("instructions  bytes   ns/call  ns/instruction  bytes/ns");
        for (name, len, fs) in sets {
            println!("{name} instructions:");
            for (n, f) in fs {
                let ns = best(f);
                println!("{n:12} {:6} {ns:9.1} {:15.4} {:9.1}", n * len, ns / n as f64, (n * len) as f64 / ns);
            }
        }
    }
}

fn main() {
    #[cfg(target_arch = "x86_64")]
    x86::main();
    #[cfg(not(target_arch = "x86_64"))]
    println!("this example measures x86-64 processors only");
}
