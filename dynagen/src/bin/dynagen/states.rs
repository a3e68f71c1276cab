//! Reading the states of `dynagen eval`: JSON in, checked vectors out.
//! Every message names the state (counting from 0), the field and, for a
//! bad entry, its index and joint (or a floating base's coordinate).

use dynagen::Model;
use nalgebra::DVector;
use serde_json::Value;
use std::fmt;

/// What an entry of a state vector is, for messages: a joint's, or one of
/// a floating base's coordinates.
#[derive(Clone, Debug)]
pub enum Entry {
    /// The joint of this name.
    Joint(String),
    /// A floating base's coordinate (`base quaternion w`, `base angular x`).
    Base(&'static str),
}

impl fmt::Display for Entry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Entry::Joint(name) => write!(f, "joint \"{name}\""),
            Entry::Base(what) => f.write_str(what),
        }
    }
}

/// A floating base's entries of q: its position and quaternion.
const BASE_Q: [&str; 7] = [
    "base position x",
    "base position y",
    "base position z",
    "base quaternion x",
    "base quaternion y",
    "base quaternion z",
    "base quaternion w",
];
/// A floating base's entries of the velocity side: its body twist.
const BASE_V: [&str; 6] =
    ["base angular x", "base angular y", "base angular z", "base linear x", "base linear y", "base linear z"];

/// The entries of a robot's states: q's (NQ), and the velocity side's
/// (NV: qd, qdd, tau and every output), with the joint names.
#[derive(Clone, Debug)]
pub struct Layout {
    /// The joint names, in order.
    pub joints: Vec<String>,
    /// The entries of q: the joints, after a floating base's position and
    /// quaternion.
    pub q: Vec<Entry>,
    /// The entries of qd, qdd and tau: the joints, after a floating base's
    /// twist (angular, then linear).
    pub v: Vec<Entry>,
}

impl Layout {
    /// The layout of `model`'s states.
    pub fn of(model: &Model) -> Self {
        let joints: Vec<String> = model.joint_names().iter().map(|s| s.to_string()).collect();
        let named = joints.iter().map(|j| Entry::Joint(j.clone()));
        let (q_base, v_base): (&[&'static str], &[&'static str]) =
            if model.is_floating() { (&BASE_Q, &BASE_V) } else { (&[], &[]) };
        let q = q_base.iter().map(|b| Entry::Base(b)).chain(named.clone()).collect();
        let v = v_base.iter().map(|b| Entry::Base(b)).chain(named).collect();
        Layout { joints, q, v }
    }
    /// Whether the robot floats.
    fn floating(&self) -> bool {
        self.q.len() > self.joints.len()
    }
    /// The entries of the field `name`.
    pub fn entries(&self, name: &str) -> &[Entry] {
        if name == "q" {
            &self.q
        } else {
            &self.v
        }
    }
    /// How many entries the field `name` must have, in words.
    fn expected(&self, name: &str) -> String {
        let n = self.joints.len();
        match (self.floating(), name) {
            (false, _) => format!("the robot has {n} joints"),
            (true, "q") => format!("a floating-base q has NQ = {} (position, quaternion x y z w, {n} joints)", n + 7),
            (true, _) => format!("a floating-base \"{name}\" has NV = {} (base twist, {n} joints)", n + 6),
        }
    }
}

/// The fields of a state.
const FIELDS: [&str; 4] = ["q", "qd", "qdd", "tau"];

/// One state: each field present or not.
#[derive(Debug)]
pub struct State {
    /// Joint positions (required).
    pub q: DVector<f64>,
    /// Joint velocities.
    pub qd: Option<DVector<f64>>,
    /// Joint accelerations.
    pub qdd: Option<DVector<f64>>,
    /// Joint torques and forces.
    pub tau: Option<DVector<f64>>,
}

/// What a JSON value is, for messages.
fn kind(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("a boolean ({b})"),
        Value::Number(n) => format!("a number ({n})"),
        Value::String(s) => format!("a string ({})", Value::String(truncate(s))),
        Value::Array(a) => format!("an array of {} entries", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

fn truncate(s: &str) -> String {
    if s.chars().count() > 40 {
        s.chars().take(40).chain("…".chars()).collect()
    } else {
        s.to_string()
    }
}

/// A JSON value read with every object's keys checked to be distinct:
/// serde_json's `Value` keeps the last of two equal keys without a word, so
/// `{"states": [...], "states": []}` would evaluate nothing.
struct Distinct(Value);

impl<'de> serde::Deserialize<'de> for Distinct {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(DistinctVisitor)
    }
}

struct DistinctVisitor;

impl<'de> serde::de::Visitor<'de> for DistinctVisitor {
    type Value = Distinct;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Distinct, E> {
        Ok(Distinct(Value::Bool(v)))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Distinct, E> {
        Ok(Distinct(Value::from(v)))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Distinct, E> {
        Ok(Distinct(Value::from(v)))
    }
    fn visit_f64<E>(self, v: f64) -> Result<Distinct, E> {
        Ok(Distinct(Value::from(v)))
    }
    fn visit_str<E>(self, v: &str) -> Result<Distinct, E> {
        Ok(Distinct(Value::String(v.to_string())))
    }
    fn visit_unit<E>(self) -> Result<Distinct, E> {
        Ok(Distinct(Value::Null))
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Distinct, A::Error> {
        let mut out = Vec::new();
        while let Some(Distinct(v)) = seq.next_element()? {
            out.push(v);
        }
        Ok(Distinct(Value::Array(out)))
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Distinct, A::Error> {
        let mut out = serde_json::Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if out.contains_key(&key) {
                return Err(serde::de::Error::custom(format!("duplicate key \"{key}\"")));
            }
            let Distinct(v) = map.next_value()?;
            out.insert(key, v);
        }
        Ok(Distinct(Value::Object(out)))
    }
}

/// Parses and checks the whole input; errors name the state and the field.
/// A UTF-8 byte-order mark at the start is skipped (editors on Windows
/// write one; the URDF reader skips it too).
pub fn parse_states(text: &str, layout: &Layout) -> Result<Vec<State>, String> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let Distinct(doc) = serde_json::from_str(text).map_err(|e| parse_error(text, &e, layout))?;
    let Value::Object(top) = doc else {
        return Err(format!("expected an object {{\"states\": [...]}} at the top level, found {}", kind(&doc)));
    };
    for key in top.keys() {
        if key != "states" && key != "joint_names" {
            return Err(format!(
                "unknown top-level field \"{key}\" (expected \"states\" and optionally \"joint_names\")"
            ));
        }
    }
    if let Some(names) = top.get("joint_names") {
        check_joint_names(names, &layout.joints)?;
    }
    let states = match top.get("states") {
        None => return Err("no \"states\" field (expected {\"states\": [{\"q\": [...], ...}, ...]})".into()),
        Some(Value::Array(a)) => a,
        Some(other) => return Err(format!("\"states\" must be an array of states, found {}", kind(other))),
    };
    states.iter().enumerate().map(|(i, s)| parse_state(s, layout).map_err(|e| format!("state {i}: {e}"))).collect()
}

fn check_joint_names(names: &Value, joint_names: &[String]) -> Result<(), String> {
    let expected = || format!("[{}]", joint_names.join(", "));
    let Value::Array(names) = names else {
        return Err(format!("\"joint_names\" must be an array of strings, found {}", kind(names)));
    };
    let given: Vec<&str> = names
        .iter()
        .enumerate()
        .map(|(k, v)| v.as_str().ok_or_else(|| format!("\"joint_names\"[{k}] is {}, not a string", kind(v))))
        .collect::<Result<_, _>>()?;
    if given.len() != joint_names.len() {
        return Err(format!(
            "\"joint_names\" has {} entries, the robot has {} joints {}",
            given.len(),
            joint_names.len(),
            expected()
        ));
    }
    if let Some(k) = (0..given.len()).find(|&k| given[k] != joint_names[k]) {
        return Err(format!(
            "\"joint_names\"[{k}] is \"{}\", but the robot's joint {k} is \"{}\" (the robot's order: {})",
            given[k],
            joint_names[k],
            expected()
        ));
    }
    Ok(())
}

fn parse_state(v: &Value, layout: &Layout) -> Result<State, String> {
    let Value::Object(fields) = v else {
        return Err(format!(
            "expected an object with \"q\" (and optionally \"qd\", \"qdd\", \"tau\"), found {}",
            kind(v)
        ));
    };
    for key in fields.keys() {
        if !FIELDS.contains(&key.as_str()) {
            return Err(format!("unknown field \"{key}\" (the fields are \"q\", \"qd\", \"qdd\", \"tau\")"));
        }
    }
    let field = |name: &str| -> Result<Option<DVector<f64>>, String> {
        fields.get(name).map(|v| parse_vector(name, v, layout)).transpose()
    };
    Ok(State {
        q: field("q")?.ok_or("\"q\" is missing (it is required; the other fields are optional)")?,
        qd: field("qd")?,
        qdd: field("qdd")?,
        tau: field("tau")?,
    })
}

fn parse_vector(name: &str, v: &Value, layout: &Layout) -> Result<DVector<f64>, String> {
    let entries = layout.entries(name);
    let items = match v {
        Value::Array(a) => a,
        Value::Null => {
            return Err(format!("\"{name}\" is null (leave the field out to skip the outputs that need it)"))
        }
        other => return Err(format!("\"{name}\" must be an array of numbers, one per joint, found {}", kind(other))),
    };
    if items.len() != entries.len() {
        return Err(format!("\"{name}\" has {} entries, {}", items.len(), layout.expected(name)));
    }
    let mut x = DVector::zeros(items.len());
    for (k, item) in items.iter().enumerate() {
        let entry = &entries[k];
        x[k] = match item.as_f64() {
            Some(value) if value.is_finite() => value,
            Some(value) => return Err(format!("\"{name}\"[{k}] ({entry}) is {value}, not a finite number")),
            None => return Err(format!("\"{name}\"[{k}] ({entry}) is {}, not a number", kind(item))),
        };
    }
    Ok(x)
}

/// A JSON syntax error, with the place it is in (`state 3: "qd"[2] (joint
/// "elbow")`) when the text up to the error says. serde_json refuses numbers
/// beyond f64's range (1e400) while parsing, so this is where they end up.
fn parse_error(text: &str, e: &serde_json::Error, layout: &Layout) -> String {
    let what = if e.to_string().starts_with("number out of range") {
        format!("a number too large for f64 (line {} column {})", e.line(), e.column())
    } else if let Some(key) = e.to_string().strip_prefix("duplicate key ").and_then(|k| k.split(" at line").next()) {
        format!(
            "the key {key} appears twice in one object (line {} column {}): JSON readers differ on which one counts, so give it once",
            e.line(),
            e.column()
        )
    } else {
        format!("malformed JSON: {e}")
    };
    // At the end of the text, serde_json points at the last character read
    // rather than at an offending one: everything has been read.
    let path = if e.is_eof() { locate(text, usize::MAX, 0) } else { locate(text, e.line(), e.column()) };
    match path.and_then(|path| describe(&path, layout)) {
        Some(place) => format!("{place}: {what}"),
        None => what,
    }
}

/// A step into a JSON document: an object's key or an array's index.
#[derive(Debug, PartialEq)]
enum Step {
    Key(String),
    Index(usize),
}

/// The path to the value being read at (line, column), both from 1 as
/// serde_json counts them (column in bytes, pointing at the offending
/// character), found by scanning the text before that character; a line
/// past the end scans the whole text. The text before an error is valid JSON so far, so tracking
/// brackets, strings, colons and commas is enough.
fn locate(text: &str, line: usize, column: usize) -> Option<Vec<Step>> {
    let line_start: usize = text.split_inclusive('\n').take(line.checked_sub(1)?).map(str::len).sum();
    let end = line_start.saturating_add(column.saturating_sub(1)).min(text.len());
    // Each open container: an array with its index, or an object with the
    // key read last (None while a key is expected).
    let mut stack: Vec<(bool, usize, Option<String>)> = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < end {
        match bytes[i] {
            b'"' => {
                let start = i + 1;
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                if let Some((false, _, key @ None)) = stack.last_mut() {
                    *key = Some(text.get(start..i.min(text.len()))?.to_string());
                }
            }
            b'{' => stack.push((false, 0, None)),
            b'[' => stack.push((true, 0, None)),
            b'}' | b']' => {
                stack.pop();
            }
            b',' => match stack.last_mut() {
                Some((true, index, _)) => *index += 1,
                Some((false, _, key)) => *key = None,
                None => {}
            },
            _ => {}
        }
        i += 1;
    }
    Some(
        stack
            .into_iter()
            .filter_map(|(array, index, key)| if array { Some(Step::Index(index)) } else { key.map(Step::Key) })
            .collect(),
    )
}

/// `state 3: "qd"[2] (joint "elbow")`, or as much of it as the path has.
fn describe(path: &[Step], layout: &Layout) -> Option<String> {
    match path {
        [Step::Key(states), Step::Index(i), rest @ ..] if states == "states" => Some(match rest {
            [Step::Key(field), Step::Index(k), ..] => match layout.entries(field).get(*k) {
                Some(entry) => format!("state {i}: \"{field}\"[{k}] ({entry})"),
                None => format!("state {i}: \"{field}\"[{k}]"),
            },
            [Step::Key(field), ..] => format!("state {i}: \"{field}\""),
            _ => format!("state {i}"),
        }),
        [Step::Key(key), ..] => Some(format!("\"{key}\"")),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> Layout {
        let joints: Vec<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
        let entries: Vec<Entry> = joints.iter().map(|j| Entry::Joint(j.clone())).collect();
        Layout { joints, q: entries.clone(), v: entries }
    }

    #[test]
    fn a_number_too_large_is_located() {
        let text = "{\"states\": [{\"q\": [0, 0, 0]},\n {\"q\": [0, 0, 0], \"qd\": [1, 1e400, 0]}]}";
        let e = parse_states(text, &names()).unwrap_err();
        assert!(e.starts_with("state 1: \"qd\"[1] (joint \"b\"): a number too large for f64 (line 2"), "{e}");
    }

    #[test]
    fn strings_with_brackets_and_escapes_do_not_confuse_the_locator() {
        let text = "{\"states\": [{\"q\": [0, 0, 0], \"x\\\"[,\": 0}, {\"q\": [0, 0, 0], \"qd\": [1, 2, }]}";
        let e = parse_states(text, &names()).unwrap_err();
        assert!(e.starts_with("state 1: \"qd\"[2] (joint \"c\"): malformed JSON"), "{e}");
    }

    #[test]
    fn a_key_not_yet_followed_by_a_value_is_the_place() {
        let text = "{\"states\": [{\"q\": ]}";
        let e = parse_states(text, &names()).unwrap_err();
        assert!(e.starts_with("state 0: \"q\": malformed JSON"), "{e}");
    }

    #[test]
    fn a_duplicate_key_is_refused_naming_it() {
        // serde_json's Value would keep the last "states" and evaluate nothing
        let e = parse_states("{\"states\": [{\"q\": [0, 0, 0]}], \"states\": []}", &names()).unwrap_err();
        assert!(e.contains("the key \"states\" appears twice in one object (line 1 column"), "{e}");
        let e = parse_states("{\"states\": [{\"q\": [0, 0, 0], \"qd\": [1, 2, 3], \"qd\": [0, 0, 0]}]}", &names())
            .unwrap_err();
        assert!(e.starts_with("state 0: ") && e.contains("the key \"qd\" appears twice"), "{e}");
        // equal keys in different objects are fine
        assert_eq!(parse_states("{\"states\": [{\"q\": [0, 0, 0]}, {\"q\": [1, 2, 3]}]}", &names()).unwrap().len(), 2);
    }

    #[test]
    fn a_byte_order_mark_is_skipped() {
        let states = parse_states("\u{feff}{\"states\": [{\"q\": [0, 1, 2]}]}", &names()).unwrap();
        assert_eq!(states[0].q.as_slice(), [0.0, 1.0, 2.0]);
    }
}
