//! The scene options of the macros: `scene = "file.toml"` or inline keys
//! (`gravity = none`, `lock = { wrist_3_joint = 0.0 }`, …), collected into a
//! [`dynagen::scene::Scene`], with the span of every name given so that an
//! error about a link or joint points at it.

use crate::robot::{array, Num};
use dynagen::codegen::BuildError;
use dynagen::codegen::{CodegenOptions, Function, Trig};
use dynagen::scene::{Gravity, PayloadInertia, Scene, SceneFile};
use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{braced, bracketed, Ident, LitStr, Token};

/// The scene keys, for error messages.
pub(crate) const SCENE_KEYS: &str = "scene, gravity, tip_wrench, subtree, lock, armature, viscous, coulomb, \
                                     coulomb_velocity, payload, payload_input, frame_pose, frame_jacobian, \
                                     frame_world_jacobian, frame_acceleration_bias, target";

/// A link, joint or frame name: an identifier or a string.
struct Name(String, Span);

impl Parse for Name {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        if input.peek(LitStr) {
            let s: LitStr = input.parse()?;
            Ok(Name(s.value(), s.span()))
        } else {
            let i: Ident = input.parse().map_err(|e| syn::Error::new(e.span(), "expected a link or joint name"))?;
            Ok(Name(i.to_string(), i.span()))
        }
    }
}

/// `=` or `:`.
fn separator(input: ParseStream) -> syn::Result<()> {
    if input.peek(Token![=]) {
        input.parse::<Token![=]>()?;
    } else {
        input.parse::<Token![:]>()?;
    }
    Ok(())
}

/// `{ key = value, … }` (or `key: value`).
fn entries(input: ParseStream, mut entry: impl FnMut(&Name, ParseStream) -> syn::Result<()>) -> syn::Result<()> {
    let content;
    braced!(content in input);
    while !content.is_empty() {
        let key: Name = content.parse()?;
        separator(&content)?;
        entry(&key, &content)?;
        if content.is_empty() {
            break;
        }
        content.parse::<Token![,]>()?;
    }
    Ok(())
}

/// `[name, …]`.
fn names(input: ParseStream) -> syn::Result<Vec<Name>> {
    let content;
    bracketed!(content in input);
    let list: Punctuated<Name, Token![,]> = content.parse_terminated(Name::parse, Token![,])?;
    Ok(list.into_iter().collect())
}

/// One inline key, as a change to a scene.
type Edit = Box<dyn Fn(SceneFile) -> SceneFile>;

/// The scene a macro was given: a file, inline keys, or both (the keys
/// then change the file's scene, in the order given).
#[derive(Default)]
pub(crate) struct SceneOptions {
    /// `scene = "path.toml"`.
    pub(crate) file: Option<LitStr>,
    /// The inline keys, in order.
    edits: Vec<Edit>,
    /// `KEY.JOINT` of every inline per-joint value (lock, armature,
    /// friction), to refuse one given twice.
    joint_values: std::collections::HashSet<String>,
    /// Every name given inline, in order, with its span.
    spans: Vec<(String, Span)>,
    /// The first scene key's span (for errors that name no item).
    first_key: Option<Span>,
}

impl SceneOptions {
    fn edit(&mut self, f: impl Fn(Scene) -> Scene + 'static) {
        self.edits.push(Box::new(move |mut file: SceneFile| {
            file.scene = f(file.scene);
            file
        }));
    }
    /// An edit of the code keys (frame functions, target).
    fn edit_code(&mut self, f: impl Fn(SceneFile) -> SceneFile + 'static) {
        self.edits.push(Box::new(f));
    }
    fn name(&mut self, n: &Name) -> String {
        self.spans.push((n.0.clone(), n.1));
        n.0.clone()
    }

    /// Parses the value of scene key `key`, or returns `Ok(false)` when it is
    /// not one.
    pub(crate) fn parse_value(&mut self, key: &Ident, input: ParseStream) -> syn::Result<bool> {
        let k = key.to_string();
        if !SCENE_KEYS.split(", ").any(|s| s.trim() == k) {
            return Ok(false);
        }
        self.first_key.get_or_insert(key.span());
        if k == "scene" {
            let path: LitStr = input.parse()?;
            if self.file.is_some() {
                return Err(syn::Error::new(path.span(), "`scene` is given twice"));
            }
            self.file = Some(path);
            return Ok(true);
        }
        match k.as_str() {
            "gravity" => {
                let g = if input.peek(syn::token::Bracket) {
                    Gravity::Constant(array::<3>(input, "gravity")?)
                } else {
                    let v: Ident = input.parse()?;
                    match v.to_string().as_str() {
                        "none" => Gravity::None,
                        "input" => Gravity::Input,
                        "default" => Gravity::Default,
                        _ => return Err(syn::Error::new(v.span(), "expected `none`, `input`, `default` or [x, y, z]")),
                    }
                };
                self.edit(move |s| s.gravity(g));
            }
            "tip_wrench" => {
                let n: Name = input.parse()?;
                let link = self.name(&n);
                self.edit(move |s| s.tip_wrench(&link));
            }
            "subtree" => {
                let (mut root, mut tips) = (None, Vec::new());
                entries(input, |key, content| {
                    match key.0.as_str() {
                        "root" => root = Some(content.parse::<Name>()?),
                        "tips" => tips = names(content)?,
                        _ => return Err(syn::Error::new(key.1, "expected `root` or `tips`")),
                    }
                    Ok(())
                })?;
                let root = root.ok_or_else(|| syn::Error::new(key.span(), "subtree: `root = LINK` is missing"))?;
                let root = self.name(&root);
                let tips: Vec<String> = tips.iter().map(|t| self.name(t)).collect();
                self.edit(move |s| s.subtree(&root, &tips.iter().map(String::as_str).collect::<Vec<_>>()));
            }
            "lock" | "armature" | "viscous" | "coulomb" => {
                let mut list = Vec::new();
                entries(input, |joint, content| {
                    list.push((Name(joint.0.clone(), joint.1), content.parse::<Num>()?.0));
                    Ok(())
                })?;
                for (joint, x) in list {
                    if !self.joint_values.insert(format!("{k}.{}", joint.0)) {
                        return Err(syn::Error::new(joint.1, format!("{k}: joint \"{}\" is given twice", joint.0)));
                    }
                    let j = self.name(&joint);
                    let k = k.clone();
                    // An inline value replaces the scene file's for the joint.
                    self.edit(move |mut s| {
                        let list = match k.as_str() {
                            "lock" => &mut s.locks,
                            "armature" => &mut s.armature,
                            "viscous" => &mut s.viscous_friction,
                            _ => &mut s.coulomb_friction,
                        };
                        list.retain(|(name, _)| *name != j);
                        list.push((j.clone(), x));
                        s
                    });
                }
            }
            "coulomb_velocity" => {
                let v = input.parse::<Num>()?.0;
                self.edit(move |s| s.coulomb_velocity(v));
            }
            "payload" => {
                let (mut link, mut mass, mut com, mut inertia) = (None, None, [0.0; 3], [0.0; 6]);
                entries(input, |key, content| {
                    match key.0.as_str() {
                        "link" => link = Some(content.parse::<Name>()?),
                        "mass" => {
                            // The tokens of the number, for an error spanning all of it.
                            let tokens: proc_macro2::TokenStream = content.fork().parse::<Num>().map(|_| {
                                let mut t = proc_macro2::TokenStream::new();
                                let f = content.fork();
                                if let Ok(Some(minus)) = f.parse::<Option<Token![-]>>() {
                                    t.extend(quote::quote!(#minus));
                                }
                                if let Ok(lit) = f.parse::<syn::Lit>() {
                                    t.extend(quote::quote!(#lit));
                                }
                                t
                            })?;
                            let m = content.parse::<Num>()?.0;
                            if m < 0.0 {
                                return Err(syn::Error::new_spanned(tokens, format!("payload: negative mass {m} kg")));
                            }
                            mass = Some(m);
                        }
                        "com" => com = array::<3>(content, "com")?,
                        "inertia" => inertia = array::<6>(content, "inertia")?,
                        _ => return Err(syn::Error::new(key.1, "expected `link`, `mass`, `com` or `inertia`")),
                    }
                    Ok(())
                })?;
                let link = link.ok_or_else(|| syn::Error::new(key.span(), "payload: `link = LINK` is missing"))?;
                let mass = mass.ok_or_else(|| {
                    syn::Error::new(key.span(), "payload: `mass = KG` is missing (or use `payload_input = LINK`)")
                })?;
                let l = self.name(&link);
                self.edit(move |s| s.payload(&l, PayloadInertia::new(mass, com, inertia)));
            }
            "payload_input" => {
                let n: Name = input.parse()?;
                let l = self.name(&n);
                self.edit(move |s| s.payload_input(&l));
            }
            kind if Function::FRAME_KINDS.contains(&kind) => {
                for n in names(input)? {
                    let frame = Function::frame_function(kind, &self.name(&n)).expect("a frame kind");
                    self.edit_code(move |mut file| {
                        let frame = frame.clone();
                        let list = file.code.functions.get_or_insert_with(|| Function::DEFAULT.to_vec());
                        if !list.contains(&frame) {
                            list.push(frame);
                        }
                        file
                    });
                }
            }
            _ => {
                let v: Ident = input.parse()?;
                let t = match v.to_string().as_str() {
                    "std" => None,
                    "no_std_libm" => Some(Trig::Libm),
                    "no_std_sincos" => Some(Trig::Inputs),
                    _ => return Err(syn::Error::new(v.span(), "expected `std`, `no_std_libm` or `no_std_sincos`")),
                };
                self.edit_code(move |mut file| {
                    file.code.trig = t.or(file.code.trig);
                    file
                });
            }
        }
        Ok(true)
    }

    /// The message of an error of the builder, without what the macro's
    /// user already sees (the `dynagen:` prefix, which robot and scene).
    pub(crate) fn error_message(error: &BuildError) -> String {
        match error {
            BuildError::SceneRobot { source, .. } => format!("scene: {source}"),
            e => {
                let text = e.to_string();
                text.strip_prefix("dynagen: ").unwrap_or(&text).to_string()
            }
        }
    }

    /// The token an error of the builder is about: the last inline name the
    /// message quotes, else the scene file, else the first scene key.
    pub(crate) fn error_span(&self, error: &BuildError, default: Span) -> Span {
        let message = error.to_string();
        let quoted = self.spans.iter().rev().find(|(name, _)| message.contains(&format!("\"{name}\"")));
        match (quoted, &self.file, error) {
            (Some((_, span)), _, _) => *span,
            (None, Some(f), _) => f.span(),
            (None, None, BuildError::SceneRobot { .. }) => self.first_key.unwrap_or(default),
            _ => default,
        }
    }

    /// Adds the scene to `builder`: the file's (an error spanned on its path
    /// if it cannot be read or parsed), or an empty one, changed by the
    /// inline keys in order.
    pub(crate) fn apply(&self, builder: dynagen::codegen::Builder) -> syn::Result<dynagen::codegen::Builder> {
        let root = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
        let base = match &self.file {
            Some(f) => {
                let path = std::path::Path::new(&root).join(f.value());
                if !path.is_file() {
                    return Err(syn::Error::new(
                        f.span(),
                        format!(
                            "no such file: {:?} (paths are relative to the crate's root, the folder of its Cargo.toml)",
                            f.value()
                        ),
                    ));
                }
                SceneFile::from_toml_file(&path)
                    .map_err(|e| syn::Error::new(f.span(), format!("scene file {:?}: {e}", f.value())))?
            }
            None if self.edits.is_empty() => return Ok(builder),
            None => SceneFile::default(),
        };
        let file = self.edits.iter().fold(base, |s, edit| edit(s));
        Ok(builder.options(file.code.apply(CodegenOptions::default())).scene(file.scene))
    }

    /// The scene file's absolute path, for `include_bytes!`.
    pub(crate) fn file_path(&self) -> Option<String> {
        let root = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
        let path = std::path::Path::new(&root).join(self.file.as_ref()?.value());
        Some(path.canonicalize().unwrap_or(path).display().to_string())
    }
}
