//! A URDF element's attributes as the pre-check in `urdf.rs` reads them:
//! unescaped, by local name, and their numbers checked finite, with errors
//! that give the line, or the link or joint and the attribute.

use super::ModelError;
use quick_xml::events::BytesStart;

/// Reads the attributes of an element as (local name, unescaped value).
pub(super) fn attributes(
    e: &BytesStart<'_>,
    reader: &quick_xml::Reader<&[u8]>,
    xml: &str,
) -> Result<Vec<(String, String)>, ModelError> {
    let mut out = Vec::new();
    for a in e.attributes().with_checks(true) {
        let a = a.map_err(|err| malformed(xml, reader, &err.to_string()))?;
        let key = String::from_utf8_lossy(a.key.local_name().as_ref()).into_owned();
        let value =
            a.decode_and_unescape_value(reader.decoder()).map_err(|err| malformed(xml, reader, &err.to_string()))?;
        out.push((key, value.into_owned()));
    }
    Ok(out)
}

/// The line (1-based) of a byte offset.
fn line_of(xml: &str, pos: u64) -> usize {
    let pos = usize::try_from(pos).unwrap_or(usize::MAX).min(xml.len());
    xml.as_bytes()[..pos].iter().filter(|&&b| b == b'\n').count() + 1
}

pub(super) fn malformed(xml: &str, reader: &quick_xml::Reader<&[u8]>, why: &str) -> ModelError {
    ModelError::Urdf(format!("line {}: {why}", line_of(xml, reader.buffer_position())))
}

/// Parses `text` as exactly `N` finite numbers separated by white space.
pub(super) fn numbers<const N: usize>(item: &str, what: &str, text: &str) -> Result<[f64; N], ModelError> {
    let bad = || ModelError::BadNumber { item: item.to_string(), what: what.to_string(), text: text.to_string() };
    let mut out = [0.0; N];
    let mut tokens = text.split_whitespace();
    for x in &mut out {
        *x = tokens.next().and_then(|t| t.parse::<f64>().ok()).filter(|x| x.is_finite()).ok_or_else(bad)?;
    }
    if tokens.next().is_some() {
        return Err(bad());
    }
    Ok(out)
}

pub(super) fn get<'a>(attrs: &'a [(String, String)], key: &str) -> Option<&'a str> {
    attrs.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
}

/// Checks the numbers of an element: each of `keys` that is present must be
/// `N` finite numbers (every attribute with that local name, so a prefixed
/// duplicate cannot slip past); those in `required` must be present.
pub(super) fn check_numbers<const N: usize>(
    attrs: &[(String, String)],
    item: &str,
    element: &str,
    keys: &[&str],
    required: &[&str],
) -> Result<(), ModelError> {
    for (k, v) in attrs {
        if keys.contains(&k.as_str()) {
            numbers::<N>(item, &format!("{element} {k}"), v)?;
        }
    }
    for k in required {
        if get(attrs, k).is_none() {
            return Err(ModelError::Urdf(format!("{item}: <{element}> has no {k} attribute")));
        }
    }
    Ok(())
}

/// Checks an `<origin>`: xyz and rpy three finite numbers each; from URDF
/// 1.1 on, `quat_xyzw` four, not all zero, and not together with rpy.
pub(super) fn check_origin(
    attrs: &[(String, String)],
    item: &str,
    element: &str,
    version: (u32, u32),
) -> Result<(), ModelError> {
    check_numbers::<3>(attrs, item, element, &["xyz", "rpy"], &[])?;
    if version >= (1, 1) {
        if let Some(q) = get(attrs, "quat_xyzw") {
            let v = numbers::<4>(item, &format!("{element} quat_xyzw"), q)?;
            if v.iter().all(|&x| x == 0.0) {
                return Err(ModelError::BadNumber {
                    item: item.to_string(),
                    what: format!("{element} quat_xyzw (a zero quaternion is no rotation)"),
                    text: q.to_string(),
                });
            }
            if get(attrs, "rpy").is_some() {
                return Err(ModelError::Urdf(format!("{item}: <{element}> has both rpy and quat_xyzw")));
            }
        }
    }
    Ok(())
}

/// The `version` attribute of `<robot>` as urdf-rs reads it: "major.minor",
/// anything else (or nothing) is 1.0.
pub(super) fn urdf_version(attrs: &[(String, String)]) -> (u32, u32) {
    get(attrs, "version")
        .and_then(|v| {
            let (major, minor) = v.trim().split_once('.')?;
            Some((major.parse().ok()?, minor.parse().ok()?))
        })
        .unwrap_or((1, 0))
}
