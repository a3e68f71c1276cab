//! URDF documents built from structured random input: links and joints drawn
//! from a small pool of names (so duplicates, dangling links, cycles, self
//! loops and several roots are common), with numbers that are ordinary,
//! huge, tiny, non-finite or not numbers at all. Reaches the tree and
//! inertia logic far more often than random bytes do.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use std::fmt::Write;

#[path = "common.rs"]
mod common;

const NAMES: [&str; 10] = ["base", "a", "b", "c", "d", "e", "f", "", "a b", "ü&amp;"];
const TYPES: [&str; 9] =
    ["revolute", "continuous", "prismatic", "fixed", "fixed", "floating", "planar", "spherical", "screw"];
const TOKENS: [&str; 14] =
    ["nan", "inf", "-inf", "1e308", "-1e308", "1e400", "1e-320", "abc", "", "1,5", "0x10", "+.5", "5.", "-0"];

#[derive(Arbitrary, Debug)]
enum Num {
    Small(i8),
    Any(f64),
    Token(u8),
}

impl Num {
    fn text(&self) -> String {
        match self {
            Num::Small(i) => format!("{}", f64::from(*i) / 8.0),
            Num::Any(x) => format!("{x:e}"),
            Num::Token(t) => TOKENS[usize::from(*t) % TOKENS.len()].to_string(),
        }
    }
}

fn nums(ns: &[Num]) -> String {
    ns.iter().map(Num::text).collect::<Vec<_>>().join(" ")
}

#[derive(Arbitrary, Debug)]
struct Origin {
    xyz: Option<[Num; 3]>,
    rpy: Option<[Num; 3]>,
}

impl Origin {
    fn write(&self, out: &mut String) {
        out.push_str("<origin");
        if let Some(x) = &self.xyz {
            let _ = write!(out, " xyz=\"{}\"", nums(x));
        }
        if let Some(r) = &self.rpy {
            let _ = write!(out, " rpy=\"{}\"", nums(r));
        }
        out.push_str("/>");
    }
}

#[derive(Arbitrary, Debug)]
struct Inertial {
    origin: Option<Origin>,
    mass: Option<Num>,
    inertia: Option<[Num; 6]>,
    diagonal: Option<[u8; 3]>,
}

#[derive(Arbitrary, Debug)]
struct Link {
    name: u8,
    inertial: Option<Inertial>,
}

#[derive(Arbitrary, Debug)]
struct Joint {
    name: u8,
    kind: u8,
    parent: Option<u8>,
    child: Option<u8>,
    origin: Option<Origin>,
    axis: Option<[Num; 3]>,
    limit: Option<[Num; 4]>,
    mimic: bool,
}

#[derive(Arbitrary, Debug)]
struct Doc {
    version: u8,
    links: Vec<Link>,
    joints: Vec<Joint>,
    /// a chain of this many extra links (modulo 48)
    chain: u8,
}

fn name(i: u8) -> &'static str {
    NAMES[usize::from(i) % NAMES.len()]
}

impl Doc {
    fn xml(&self) -> String {
        let version = ["", " version=\"1.0\"", " version=\"1.1\"", " version=\"1.2\""][usize::from(self.version) % 4];
        let mut out = format!("<robot name=\"fuzz\"{version}>");
        for l in &self.links {
            let _ = write!(out, "<link name=\"{}\">", name(l.name));
            if let Some(i) = &l.inertial {
                out.push_str("<inertial>");
                if let Some(o) = &i.origin {
                    o.write(&mut out);
                }
                if let Some(m) = &i.mass {
                    let _ = write!(out, "<mass value=\"{}\"/>", m.text());
                }
                if let Some(d) = &i.diagonal {
                    // a physical inertia more often than random numbers give one
                    let [a, b, c] = d.map(|x| f64::from(x) / 16.0 + 0.01);
                    let _ = write!(
                        out,
                        "<inertia ixx=\"{}\" iyy=\"{}\" izz=\"{}\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>",
                        a + b,
                        b + c,
                        a + c
                    );
                } else if let Some(n) = &i.inertia {
                    let t: Vec<String> = n.iter().map(Num::text).collect();
                    let _ = write!(
                        out,
                        "<inertia ixx=\"{}\" iyy=\"{}\" izz=\"{}\" ixy=\"{}\" ixz=\"{}\" iyz=\"{}\"/>",
                        t[0], t[1], t[2], t[3], t[4], t[5]
                    );
                }
                out.push_str("</inertial>");
            }
            out.push_str("</link>");
        }
        for (k, j) in self.joints.iter().enumerate() {
            let _ = write!(
                out,
                "<joint name=\"j{}{}\" type=\"{}\">",
                name(j.name),
                k % 3,
                TYPES[usize::from(j.kind) % TYPES.len()]
            );
            if let Some(p) = j.parent {
                let _ = write!(out, "<parent link=\"{}\"/>", name(p));
            }
            if let Some(c) = j.child {
                let _ = write!(out, "<child link=\"{}\"/>", name(c));
            }
            if let Some(o) = &j.origin {
                o.write(&mut out);
            }
            if let Some(a) = &j.axis {
                let _ = write!(out, "<axis xyz=\"{}\"/>", nums(a));
            }
            if let Some([lo, up, ef, ve]) = &j.limit {
                let _ = write!(
                    out,
                    "<limit lower=\"{}\" upper=\"{}\" effort=\"{}\" velocity=\"{}\"/>",
                    lo.text(),
                    up.text(),
                    ef.text(),
                    ve.text()
                );
            }
            if j.mimic {
                out.push_str("<mimic joint=\"x\"/>");
            }
            out.push_str("</joint>");
        }
        let first = self.links.first().map_or("base", |l| name(l.name));
        // up to 47 more links: long enough for deep trees, short enough to
        // keep thousands of runs a second (the 10,000-link chain is a test)
        for k in 0..usize::from(self.chain % 48) {
            let parent = if k == 0 { first.to_string() } else { format!("chain{}", k - 1) };
            let _ = write!(
                out,
                "<link name=\"chain{k}\"><inertial><mass value=\"1\"/>\
                 <inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\
                 <joint name=\"chain{k}\" type=\"{}\"><parent link=\"{parent}\"/><child link=\"chain{k}\"/>\
                 <origin xyz=\"0 0 0.1\"/><axis xyz=\"0 1 0\"/></joint>",
                if k % 3 == 2 { "fixed" } else { "continuous" }
            );
        }
        out.push_str("</robot>");
        out
    }
}

fuzz_target!(|doc: Doc| {
    let xml = doc.xml();
    if let Ok(model) = dynagen::Model::from_urdf_str(&xml) {
        common::exercise(model);
    }
});
