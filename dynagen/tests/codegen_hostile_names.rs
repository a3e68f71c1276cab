//! Names from a robot file never become code. `data/hostile_names.urdf` and
//! `data/hostile_names.toml` put newlines, CR, `*/`, quotes, backslashes,
//! U+2028/U+2029, bidirectional controls, NEL, DEL and tabs into the robot's,
//! every link's, joint's and frame's name and the scene's name, and the
//! file's own path holds a newline; every such text reaches the header (a
//! `//` comment), the doc comments, `JOINT_NAMES` and the frame functions'
//! identifiers. Through the `Builder` and `dynagen generate` (the macros are
//! tested in `dynagen-macros` and `tests/user-macro`), the module must
//! hold exactly the items of the same module made from harmless names,
//! `JOINT_NAMES` must read back as the names, and rustc must compile it with
//! `-D warnings` and find no `injected` in it.

use dynagen::codegen::{generate, Builder, CodegenOptions, Function};
use dynagen::model::{Inertial, JointDescription, RobotBuilder};
use quote::ToTokens;
use std::path::{Path, PathBuf};

const INJECTED: &str = "pub fn injected() -> u32 { 42 }";

/// The robot's and scene's names, as `data/hostile_names.*` write them.
fn hostile_links() -> Vec<String> {
    vec![
        "base".to_string(),
        format!("a\n{INJECTED}\n//"),
        format!("b\r\n{INJECTED}\r//"),
        format!("c */ {INJECTED} /* `</code><script>`"),
        format!("d\u{2028}{INJECTED}\u{2029}//"),
        "e\u{202e}\u{2066}rtl\u{2069}\u{202c}\u{200f}".to_string(),
        format!("f\"); {INJECTED} //\\"),
        "g\u{85}\u{7f}\t\\u{a}".to_string(),
        "h\n}\nfn injected() {\n".to_string(),
    ]
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

/// A fresh directory for one test's files.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("hostile_names").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Characters that must not appear as themselves anywhere in a module (the
/// line feed aside): control characters, line and paragraph separators,
/// bidirectional controls.
fn raw_unsafe(c: char) -> bool {
    (c.is_control() && c != '\n')
        || matches!(c, '\u{2028}' | '\u{2029}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{200e}' | '\u{200f}')
}

/// Every item of a module, as `kind name`, frame functions' names cut after
/// their prefix (they are made from the frame's name).
fn items(source: &str) -> Vec<String> {
    let file = syn::parse_file(source).unwrap_or_else(|e| panic!("the module does not parse: {e}"));
    let mut out: Vec<String> = file
        .items
        .iter()
        .map(|item| {
            let (kind, name) = match item {
                syn::Item::Fn(f) => ("fn", f.sig.ident.to_string()),
                syn::Item::Const(c) => ("const", c.ident.to_string()),
                syn::Item::Static(s) => ("static", s.ident.to_string()),
                syn::Item::Trait(t) => ("trait", t.ident.to_string()),
                syn::Item::Struct(s) => ("struct", s.ident.to_string()),
                syn::Item::Impl(i) => ("impl", quote_of(&i.self_ty)),
                other => ("other", other.to_token_stream().to_string()),
            };
            let name = ["frame_pose_", "frame_jacobian_"]
                .iter()
                .find(|p| name.starts_with(*p))
                .map_or(name.clone(), |p| format!("{p}FRAME{}", if name.ends_with("_sc") { "_sc" } else { "" }));
            format!("{kind} {name}")
        })
        .collect();
    out.sort();
    out
}

fn quote_of(t: &syn::Type) -> String {
    match t {
        syn::Type::Path(p) => p.path.segments.iter().map(|s| s.ident.to_string()).collect::<Vec<_>>().join("::"),
        _ => "type".into(),
    }
}

/// `JOINT_NAMES`' values, read back from the module's literal.
fn joint_names(source: &str) -> Vec<String> {
    let file = syn::parse_file(source).unwrap();
    for item in &file.items {
        if let syn::Item::Const(c) = item {
            if c.ident == "JOINT_NAMES" {
                let syn::Expr::Array(a) = &*c.expr else { panic!("JOINT_NAMES is not an array") };
                return a
                    .elems
                    .iter()
                    .map(|e| match e {
                        syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }) => s.value(),
                        other => panic!("not a string literal: {}", other.to_token_stream()),
                    })
                    .collect();
            }
        }
    }
    panic!("no JOINT_NAMES")
}

/// What every module made from hostile names must be: its header plain `//`
/// lines, no unsafe character anywhere, its items those of `benign`, its
/// `JOINT_NAMES` the names.
fn check_module(source: &str, benign: &str, names: &[String]) {
    for (i, line) in source.split('\n').enumerate() {
        assert!(!line.chars().any(raw_unsafe), "line {} holds a raw control character: {line:?}", i + 1);
    }
    for line in source.lines().take_while(|l| l.starts_with("//")) {
        assert!(line == "//" || line.starts_with("// "), "a header line that is not a plain comment: {line:?}");
    }
    let got = items(source);
    assert!(!got.iter().any(|i| i.contains("injected")), "{got:?}");
    assert_eq!(got, items(benign), "the module's items differ from those of the same robot with harmless names");
    assert_eq!(joint_names(source), names);
}

/// The same robot and scene with every name replaced by a harmless one.
fn benign_copies(dir: &Path) -> (PathBuf, PathBuf) {
    let mut urdf = std::fs::read_to_string(data("hostile_names.urdf")).unwrap();
    let mut toml = std::fs::read_to_string(data("hostile_names.toml")).unwrap();
    let xml = |s: &str| {
        s.chars()
            .map(|c| match c {
                '&' => "&amp;".into(),
                '<' => "&lt;".into(),
                '>' => "&gt;".into(),
                '"' => "&quot;".into(),
                c if (c as u32) < 0x20 || (c as u32) >= 0x7f => format!("&#x{:x};", c as u32),
                c => c.to_string(),
            })
            .collect::<String>()
    };
    let toml_str = |s: &str| {
        let mut out = String::from("\"");
        for c in s.chars() {
            match c {
                '"' => out.push_str("\\\""),
                '\\' => out.push_str("\\\\"),
                c if (c as u32) < 0x20 || (c as u32) >= 0x7f => out.push_str(&format!("\\u{:04X}", c as u32)),
                c => out.push(c),
            }
        }
        out + "\""
    };
    let links = hostile_links();
    // Joints are named as their link, with a `J` for the first letter.
    for (i, link) in links.iter().enumerate().skip(1).rev() {
        let joint = format!("J{}", &link[1..]);
        urdf = urdf.replace(&xml(link), &format!("link{i}")).replace(&xml(&joint), &format!("joint{i}"));
        toml =
            toml.replace(&toml_str(link), &format!("\"link{i}\"")).replace(&toml_str(&joint), &format!("\"joint{i}\""));
    }
    urdf = urdf.replace(&xml(&format!("x\n{INJECTED}\n//")), "robot");
    let name_line = toml.lines().find(|l| l.starts_with("name = ")).unwrap().to_string();
    toml = toml.replace(&name_line, "name = \"scene\"");
    assert!(!urdf.contains("injected") && !toml.contains("injected"), "{urdf}\n{toml}");
    let (u, t) = (dir.join("benign.urdf"), dir.join("benign.toml"));
    std::fs::write(&u, urdf).unwrap();
    std::fs::write(&t, toml).unwrap();
    (u, t)
}

/// The joint names the scene keeps (one is locked).
fn kept_joints() -> Vec<String> {
    let links = hostile_links();
    (1..8).filter(|&i| i != 5).map(|i| format!("J{}", &links[i][1..])).collect()
}

/// Compiles `lib.rs` beside the module with `-D warnings` (type-checking
/// only); returns rustc's stderr on failure.
fn rustc_check(dir: &Path, lib: &str) -> Result<(), String> {
    std::fs::write(dir.join("lib.rs"), lib).unwrap();
    let out = std::process::Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
        .args(["--edition", "2021", "--crate-type", "lib", "--emit", "metadata", "-D", "warnings", "--out-dir"])
        .arg(dir)
        .arg(dir.join("lib.rs"))
        .output()
        .expect("running rustc");
    if out.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

#[test]
fn the_urdf_parser_gives_the_names_as_written() {
    let model = dynagen::Model::from_urdf_file(data("hostile_names.urdf")).unwrap();
    assert_eq!(model.name, format!("x\n{INJECTED}\n//"));
    let names: Vec<&str> = model.frames.iter().map(|f| f.name.as_str()).collect();
    for link in hostile_links() {
        assert!(names.contains(&link.as_str()), "{link:?} not among {names:?}");
    }
}

#[test]
fn the_builder_writes_names_as_text_and_rustc_finds_nothing_else() {
    let dir = scratch("builder");
    // The robot file's own name holds the injection too: it is the header's
    // model source.
    let urdf = dir.join(format!("robot\n{INJECTED}\n\r.urdf"));
    std::fs::copy(data("hostile_names.urdf"), &urdf).unwrap();
    let written = Builder::new()
        .urdf(&urdf)
        .scene_file(data("hostile_names.toml"))
        .out_dir(&dir)
        .module_name("hostile")
        .cargo_output(false)
        .generate()
        .unwrap();
    let (benign_urdf, benign_toml) = benign_copies(&dir);
    let benign = Builder::new().urdf(benign_urdf).scene_file(benign_toml).generate_module().unwrap();
    let source = std::fs::read_to_string(&written.path).unwrap();
    check_module(&source, &benign.source, &kept_joints());
    // What the names became in the header and the docs: escaped, in place.
    assert!(
        source.starts_with(
            "// Dynamics of the robot \"x\\u{a}pub fn injected() -> u32 { 42 }\\u{a}//\" in the scene \"s\\u{a}"
        ),
        "{}",
        &source[..300]
    );
    assert!(source.contains("// Model source: ") && source.contains("robot\\u{a}pub fn injected"));
    assert!(source.contains("/// The pose of frame `h\\u{a}}\\u{a}fn injected() {\\u{a}` in the base frame"));
    assert!(source
        .contains("/// The body Jacobian of frame `` c */ pub fn injected() -> u32 { 42 } /* `</code><script>` `` (6"));
    assert!(source.contains("J\\u{202e}\\u{2066}rtl\\u{2069}\\u{202c}\\u{200f} at 0.3"), "the locked joint");

    let lib = "mod hostile {\n    include!(\"hostile.rs\");\n}\npub use hostile::*;\n";
    rustc_check(&dir, lib).unwrap_or_else(|e| panic!("the module does not compile:\n{e}"));
    let probe = format!("{lib}pub fn probe() -> u32 {{\n    hostile::injected()\n}}\n");
    let err = rustc_check(&dir, &probe).expect_err("a function `injected` exists");
    assert!(err.contains("cannot find function `injected`"), "{err}");
}

#[test]
fn dynagen_generate_writes_the_same_names_as_text() {
    let dir = scratch("cli");
    let urdf = dir.join(format!("robot\u{2028}{INJECTED}\u{202e}.urdf"));
    std::fs::copy(data("hostile_names.urdf"), &urdf).unwrap();
    let out = assert_cmd::Command::cargo_bin("dynagen")
        .unwrap()
        .arg("generate")
        .arg(&urdf)
        .arg("--scene")
        .arg(data("hostile_names.toml"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let source = String::from_utf8(out.stdout).unwrap();
    let (benign_urdf, benign_toml) = benign_copies(&dir);
    let benign = Builder::new().urdf(benign_urdf).scene_file(benign_toml).generate_module().unwrap();
    check_module(&source, &benign.source, &kept_joints());
    assert!(source.contains("robot\\u{2028}pub fn injected() -> u32 { 42 }\\u{202e}.urdf"), "the model source");
}

/// Names a URDF file cannot hold (NUL and other C0 controls), through a
/// model built in Rust, with the options' name and source.
#[test]
fn names_no_xml_can_hold_are_text_too() {
    let names: Vec<String> = (0u32..0x20)
        .chain([0x7f, 0x85, 0x2028, 0x2029, 0x202e, 0x2067, 0xfeff])
        .map(|c| format!("n{c}{}{INJECTED}", char::from_u32(c).unwrap()))
        .collect();
    let mut b = RobotBuilder::new(&format!("r\0\n{INJECTED}")).link("base", None);
    let mut parent = "base".to_string();
    for (i, name) in names.iter().take(3).enumerate() {
        b = b.link(name, Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [0.01, 0.02, 0.03, 0.0, 0.0, 0.0]))).joint(
            JointDescription::revolute(
                &format!("j{i}{name}"),
                &parent,
                name,
                [0.0, (i % 2) as f64, ((i + 1) % 2) as f64],
            ),
        );
        parent = name.clone();
    }
    let model = b.build().unwrap();
    let frames: Vec<Function> = names.iter().take(3).map(|n| Function::FramePose(n.clone())).collect();
    let mut options = CodegenOptions::default().functions(frames.into_iter().chain([Function::GravityTorques]));
    options.source = Some(format!("src\n{INJECTED}\r\u{2029}"));
    options.name = Some(format!("scene\n{INJECTED}"));
    let source = generate(&model, &options).unwrap().source;
    for (i, line) in source.split('\n').enumerate() {
        assert!(!line.chars().any(raw_unsafe), "line {}: {line:?}", i + 1);
    }
    let got = items(&source);
    assert!(!got.iter().any(|i| i.contains("injected")), "{got:?}");
    let joints: Vec<String> = names.iter().take(3).enumerate().map(|(i, n)| format!("j{i}{n}")).collect();
    assert_eq!(joint_names(&source), joints);
    // Every other name of the list reaches a frame function's doc.
    for name in names.iter().skip(3) {
        let model = RobotBuilder::new("r")
            .link("base", None)
            .link(name, Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [0.01, 0.02, 0.03, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("j", "base", name, [0.0, 0.0, 1.0]))
            .build()
            .unwrap();
        let options = CodegenOptions::default().functions([Function::FramePose(name.clone())]);
        let source = generate(&model, &options).unwrap().source;
        assert!(!source.split('\n').any(|l| l.chars().any(raw_unsafe)), "{name:?}");
        assert!(!items(&source).iter().any(|i| i.contains("injected")), "{name:?}");
    }
}

/// Names whose identifier would collide are refused, naming what collides.
#[test]
fn payload_arguments_that_would_collide_are_refused() {
    let model = RobotBuilder::new("r")
        .link("base", None)
        .link("a-b", Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [0.01, 0.02, 0.03, 0.0, 0.0, 0.0])))
        .link("a.b", Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [0.01, 0.02, 0.03, 0.0, 0.0, 0.0])))
        .joint(JointDescription::revolute("j1", "base", "a-b", [0.0, 0.0, 1.0]))
        .joint(JointDescription::revolute("j2", "a-b", "a.b", [0.0, 1.0, 0.0]))
        .build()
        .unwrap();
    let scene = dynagen::scene::Scene::new().payload_input("a-b").payload_input("a.b");
    let applied = scene.apply(&model).unwrap();
    let e = dynagen::codegen::generate_scene(&applied, &CodegenOptions::default()).unwrap_err();
    assert!(e.to_string().contains("`payload_a_b`"), "{e}");
}
