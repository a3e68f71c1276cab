//! `robot! { … }`: a robot written in Rust tokens, built with
//! [`dynagen::RobotBuilder`].

use crate::{items, MacroOptions, OPTION_NAMES};
use dynagen::codegen::Builder;
use dynagen::model::{Inertial, JointDescription};
use dynagen::RobotBuilder;
use proc_macro2::{Span, TokenStream};
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{braced, bracketed, parenthesized, Ident, Token};

/// A number literal, optionally negated.
#[derive(Clone, Copy)]
pub(crate) struct Num(pub(crate) f64);

impl Parse for Num {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let neg = input.parse::<Option<Token![-]>>()?.is_some();
        let lit: syn::Lit = input.parse().map_err(|e| syn::Error::new(e.span(), "expected a number"))?;
        let (value, span) = match &lit {
            syn::Lit::Int(i) => (i.base10_digits().parse::<f64>(), i.span()),
            syn::Lit::Float(f) => (f.base10_digits().parse::<f64>(), f.span()),
            other => return Err(syn::Error::new(other.span(), "expected a number")),
        };
        let value = value.map_err(|_| syn::Error::new(span, "expected a number"))?;
        Ok(Num(if neg { -value } else { value }))
    }
}

/// `[a, b, c, …]` with exactly `N` numbers.
pub(crate) fn array<const N: usize>(input: ParseStream, what: &str) -> syn::Result<[f64; N]> {
    let content;
    let bracket = bracketed!(content in input);
    let list: Punctuated<Num, Token![,]> = content.parse_terminated(Num::parse, Token![,])?;
    if list.len() != N {
        return Err(syn::Error::new(
            bracket.span.join(),
            format!("{what}: expected {N} numbers, found {}", list.len()),
        ));
    }
    let mut out = [0.0; N];
    for (o, n) in out.iter_mut().zip(&list) {
        *o = n.0;
    }
    Ok(out)
}

/// Reads `key: value` fields separated by commas inside braces.
fn fields(input: ParseStream, mut field: impl FnMut(&Ident, ParseStream) -> syn::Result<()>) -> syn::Result<()> {
    let content;
    braced!(content in input);
    while !content.is_empty() {
        let key: Ident = content.parse()?;
        content.parse::<Token![:]>()?;
        field(&key, &content)?;
        if content.is_empty() {
            break;
        }
        content.parse::<Token![,]>()?;
    }
    Ok(())
}

struct Link {
    name: Ident,
    inertial: Option<Inertial>,
}

struct Joint {
    name: Ident,
    kind: Ident,
    parent: Ident,
    child: Ident,
    origin: [f64; 3],
    rpy: [f64; 3],
    axis: Option<[f64; 3]>,
    limits: Option<[f64; 4]>,
    /// The master, multiplier and offset of a joint that follows another.
    mimic: Option<(Ident, f64, f64)>,
}

pub(crate) struct RobotInput {
    name: Ident,
    gravity: Option<[f64; 3]>,
    options: MacroOptions,
    links: Vec<Link>,
    joints: Vec<Joint>,
}

fn unknown(key: &Ident, known: &str) -> syn::Error {
    syn::Error::new(key.span(), format!("unknown field `{key}`; expected one of {known}"))
}

impl Parse for Link {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let name: Ident = input.parse()?;
        let (mut mass, mut com, mut inertia) = (None, [0.0; 3], [0.0; 6]);
        fields(input, |key, v| {
            match key.to_string().as_str() {
                "mass" => mass = Some(v.parse::<Num>()?.0),
                "com" => com = array(v, "com")?,
                "inertia" => inertia = array(v, "inertia")?,
                _ => return Err(unknown(key, "mass, com, inertia")),
            }
            Ok(())
        })?;
        let inertial = match mass {
            Some(m) => Some(Inertial::new(m, com, inertia)),
            None if com != [0.0; 3] || inertia != [0.0; 6] => {
                return Err(syn::Error::new(name.span(), format!("link `{name}`: `com` or `inertia` without `mass`")))
            }
            None => None,
        };
        Ok(Link { name, inertial })
    }
}

impl Parse for Joint {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let name: Ident = input.parse()?;
        input.parse::<Token![:]>()?;
        let kind: Ident = input.parse()?;
        if !["revolute", "continuous", "prismatic", "fixed"].contains(&kind.to_string().as_str()) {
            return Err(syn::Error::new(
                kind.span(),
                format!("unknown joint type `{kind}`; expected revolute, continuous, prismatic or fixed"),
            ));
        }
        let content;
        parenthesized!(content in input);
        let parent: Ident = content.parse()?;
        content.parse::<Token![->]>()?;
        let child: Ident = content.parse()?;
        let mut j =
            Joint { name, kind, parent, child, origin: [0.0; 3], rpy: [0.0; 3], axis: None, limits: None, mimic: None };
        let (mut multiplier, mut offset) = (None, None);
        fields(input, |key, v| {
            match key.to_string().as_str() {
                "origin" => j.origin = array(v, "origin")?,
                "rpy" => j.rpy = array(v, "rpy")?,
                "axis" => j.axis = Some(array(v, "axis")?),
                "limits" => j.limits = Some(array(v, "limits")?),
                "mimic" => j.mimic = Some((v.parse()?, 1.0, 0.0)),
                "multiplier" => multiplier = Some(v.parse::<Num>()?.0),
                "offset" => offset = Some(v.parse::<Num>()?.0),
                _ => return Err(unknown(key, "origin, rpy, axis, limits, mimic, multiplier, offset")),
            }
            Ok(())
        })?;
        match &mut j.mimic {
            // URDF's defaults: multiplier 1, offset 0
            Some((_, k, o)) => (*k, *o) = (multiplier.unwrap_or(1.0), offset.unwrap_or(0.0)),
            None if multiplier.is_some() || offset.is_some() => {
                return Err(syn::Error::new(
                    j.name.span(),
                    format!("joint `{}`: `multiplier` and `offset` go with `mimic: MASTER_JOINT`", j.name),
                ))
            }
            None => {}
        }
        if j.axis.is_none() && j.kind != "fixed" {
            return Err(syn::Error::new(
                j.name.span(),
                format!("joint `{}`: a {} joint needs an `axis`", j.name, j.kind),
            ));
        }
        Ok(j)
    }
}

impl Parse for RobotInput {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let key: Ident = input.parse()?;
        if key != "name" {
            return Err(syn::Error::new(key.span(), "a robot starts with `name: its_name`"));
        }
        input.parse::<Token![:]>()?;
        let name: Ident = input.parse()?;
        let mut robot =
            RobotInput { name, gravity: None, options: MacroOptions::default(), links: vec![], joints: vec![] };
        while !input.is_empty() {
            // A comma between items (optional after a `{ … }` block).
            let comma = input.parse::<Option<Token![,]>>()?;
            if input.is_empty() {
                break;
            }
            let key: Ident = input.parse()?;
            match key.to_string().as_str() {
                "link" => robot.links.push(input.parse()?),
                "joint" => robot.joints.push(input.parse()?),
                _ if comma.is_none() => return Err(syn::Error::new(key.span(), "expected `,`")),
                "gravity" => {
                    input.parse::<Token![:]>()?;
                    if input.peek(syn::token::Bracket) {
                        robot.gravity = Some(array(input, "gravity")?);
                    } else {
                        // `none`, `input` or `default`: the scene's gravity.
                        robot.options.parse_value(&key, input)?;
                    }
                }
                _ => {
                    input.parse::<Token![:]>()?;
                    if !robot.options.parse_value(&key, input)? {
                        return Err(syn::Error::new(
                            key.span(),
                            format!("unknown item `{key}`; expected `link`, `joint`, `gravity` or an option ({OPTION_NAMES})"),
                        ));
                    }
                }
            }
        }
        Ok(robot)
    }
}

/// The token a model error is about: the name (link or joint) quoted first
/// in the message; a link that does not exist is pointed at where a joint
/// names it.
fn error_span(robot: &RobotInput, message: &str) -> Span {
    fn consider(best: &mut Option<(usize, Span)>, name: &Ident, at: Option<usize>) {
        if let Some(i) = at {
            if best.is_none_or(|(b, _)| i < b) {
                *best = Some((i, name.span()));
            }
        }
    }
    let mut best = None;
    for j in &robot.joints {
        for (r, role) in [(&j.parent, "parent"), (&j.child, "child")] {
            let missing = format!("joint \"{}\": its {role} link \"{r}\" does not exist", j.name);
            consider(&mut best, r, message.find(&missing));
        }
    }
    if best.is_none() {
        for j in &robot.joints {
            consider(&mut best, &j.name, message.find(&format!("\"{}\"", j.name)));
        }
        for l in &robot.links {
            consider(&mut best, &l.name, message.find(&format!("\"{}\"", l.name)));
        }
    }
    best.map_or(robot.name.span(), |(_, s)| s)
}

pub(crate) fn expand(robot: RobotInput) -> syn::Result<TokenStream> {
    let mut b = RobotBuilder::new(&robot.name.to_string())
        .allow_nonphysical_inertia(robot.options.allow_nonphysical_inertia.unwrap_or(false))
        .mimic_joints(robot.options.mimic.unwrap_or_default());
    if let Some(g) = robot.gravity {
        b = b.gravity(g);
    }
    for l in &robot.links {
        b = b.link(&l.name.to_string(), l.inertial);
    }
    for j in &robot.joints {
        let (name, parent, child) = (j.name.to_string(), j.parent.to_string(), j.child.to_string());
        let axis = j.axis.unwrap_or_default();
        let mut d = match j.kind.to_string().as_str() {
            "revolute" => JointDescription::revolute(&name, &parent, &child, axis),
            "continuous" => JointDescription::continuous(&name, &parent, &child, axis),
            "prismatic" => JointDescription::prismatic(&name, &parent, &child, axis),
            _ => JointDescription::fixed(&name, &parent, &child),
        };
        d = d.origin(j.origin, j.rpy);
        if let Some([lo, hi, v, e]) = j.limits {
            d = d.limits(lo, hi, v, e);
        }
        if let Some((master, k, o)) = &j.mimic {
            d = d.mimic(&master.to_string(), *k, *o);
        }
        b = b.joint(d);
    }
    let model = b.build().map_err(|e| {
        let message = e.to_string();
        syn::Error::new(error_span(&robot, &message), format!("robot `{}`: {message}", robot.name))
    })?;
    let source = format!("robot! {{ name: {}, … }}", robot.name);
    let module = robot.options.apply(Builder::new().model(model), source)?.generate_module().map_err(|e| {
        syn::Error::new(robot.options.error_span(&e, robot.name.span()), crate::scene::SceneOptions::error_message(&e))
    })?;
    let scene = robot.options.rebuild_on_scene_change();
    let body = items(&module.source, robot.name.span())?;
    Ok(quote::quote! {
        #scene
        #body
    })
}
