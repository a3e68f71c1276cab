//! Text from a robot file in generated code: the one place that makes a
//! name, path or scene text safe for where it goes, and the checks that
//! nothing else got through.
//!
//! A robot file may come from anywhere, and its names reach the module: the
//! header's `//` comments (robot, scene, link, joint and frame names, the
//! model's path, the scene's TOML), doc comments (frame names), string
//! literals (`JOINT_NAMES`) and identifiers (`frame_pose_FRAME`,
//! `payload_LINK`). A newline in a name would end its comment and make the
//! rest code; a carriage return, U+2028 or U+2029 looks like a line break
//! in some editors and viewers; a bidirectional control (U+202A–U+202E,
//! U+2066–U+2069, U+200E, U+200F, U+061C) can make a line read otherwise than
//! it compiles (rustc refuses them in comments and literals). So:
//!
//! - comment text ([`comment_text`]): every such character (every control
//!   character, tab, CR and LF included, the line and paragraph separators,
//!   the bidirectional and zero-width controls, the byte-order mark) is
//!   written as a Rust escape, `\u{2028}`; quotes, backslashes and `*/` stay
//!   as they are (they mean nothing in a `//` comment, and a path such as
//!   `C:\robots\ur5.urdf` stays readable);
//! - doc text ([`doc_code`]): the same escapes, inside a Markdown code span
//!   with enough backticks that no backtick of the name ends it, so that
//!   nothing in a name is Markdown or HTML to rustdoc either;
//! - string literals: written by `quote`, which escapes as Rust's
//!   `escape_debug` does (`\n`, `\"`, `\\`, `\u{202e}`), so the literal's
//!   value is the name exactly (tests read it back);
//! - identifiers: made from a name by [`identifier_part`] (ASCII letters,
//!   digits and single `_` only) behind a prefix, then checked by
//!   [`identifier`]: an identifier that is not one, or is a keyword, is an
//!   error naming the item, never a panic or a token.
//!
//! [`check_source`] then checks the whole module: a header of `//` lines
//! only, and none of the characters above anywhere. A text that missed its
//! escaping is an error, not code.

use crate::codegen::CodegenError;

/// Whether `c` must not appear as itself in generated code: control
/// characters (C0, DEL, C1: tab, CR, LF, NEL…), the line and paragraph
/// separators, the bidirectional controls, the zero-width characters and
/// the byte-order mark.
pub(crate) fn is_unsafe_char(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{2028}'
                | '\u{2029}'
                | '\u{202A}'..='\u{202E}'
                | '\u{2066}'..='\u{2069}'
                | '\u{200B}'..='\u{200F}'
                | '\u{061C}'
                | '\u{FEFF}'
        )
}

/// `s` with every [unsafe](is_unsafe_char) character written as `\u{…}`.
fn escaped(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if is_unsafe_char(c) {
            out.push_str(&format!("\\u{{{:x}}}", c as u32));
        } else {
            out.push(c);
        }
    }
    out
}

/// A text for a `//` line comment of the header: one line, every unsafe
/// character escaped as `\u{…}` (see the module's docs).
pub(crate) fn comment_text(s: &str) -> String {
    escaped(s)
}

/// A name as a Markdown code span for a doc comment: unsafe characters
/// escaped as `\u{…}`, fenced by one backtick more than the longest run of
/// backticks in it (padded with a space where it starts or ends with one),
/// so that rustdoc shows it as code, never as Markdown or HTML.
pub(crate) fn doc_code(s: &str) -> String {
    let s = escaped(s);
    let mut longest = 0;
    let mut run = 0;
    for c in s.chars() {
        run = if c == '`' { run + 1 } else { 0 };
        longest = longest.max(run);
    }
    let fence = "`".repeat(longest + 1);
    let pad = if s.starts_with('`') || s.ends_with('`') || s.is_empty() { " " } else { "" };
    format!("{fence}{pad}{s}{pad}{fence}")
}

/// The part of an identifier made from a frame's or link's name: ASCII
/// letters (lower-cased) and digits kept, every other run of characters one
/// `_`, none at either end (so that the identifier is snake case: rustc
/// warns about `__`).
pub(crate) fn identifier_part(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.is_empty() && !out.ends_with('_') {
            out.push('_');
        }
    }
    while out.ends_with('_') {
        out.pop();
    }
    out
}

/// Rust's keywords (strict, reserved, and weak ones that cannot name an
/// item), which are not identifiers.
const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern", "false", "fn",
    "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return", "self", "Self",
    "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where", "while", "abstract", "become",
    "box", "do", "final", "gen", "macro", "override", "priv", "try", "typeof", "unsized", "virtual", "yield", "_",
];

/// Checks that `name`, made for `item` (e.g. `frame "ee link"`), is a plain
/// ASCII Rust identifier and not a keyword.
pub(crate) fn identifier(name: &str, item: &str) -> Result<(), CodegenError> {
    let mut chars = name.chars();
    let first_ok = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if first_ok && chars.all(|c| c.is_ascii_alphanumeric() || c == '_') && !KEYWORDS.contains(&name) {
        Ok(())
    } else {
        Err(CodegenError::BadIdentifier { name: name.to_string(), item: comment_text(item) })
    }
}

/// Checks a finished module: the header (the text before the first line
/// that is not a comment) is `//` comments only, and no [unsafe](is_unsafe_char)
/// character but the line feed is anywhere in it.
pub(crate) fn check_source(header: &str, source: &str) -> Result<(), CodegenError> {
    for (i, line) in header.lines().enumerate() {
        if !(line == "//" || line.starts_with("// ")) {
            return Err(CodegenError::Internal(format!("header line {} is not a plain comment: {line:?}", i + 1)));
        }
    }
    for (i, line) in source.split('\n').enumerate() {
        if let Some(c) = line.chars().find(|&c| is_unsafe_char(c)) {
            return Err(CodegenError::Internal(format!(
                "line {} holds the unescaped character U+{:04X}: {}",
                i + 1,
                c as u32,
                comment_text(line)
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comment_text_keeps_one_line_and_no_control() {
        let t = comment_text("a\nb\r\u{2028}\u{202e}c\\\"*/\t");
        assert_eq!(t, "a\\u{a}b\\u{d}\\u{2028}\\u{202e}c\\\"*/\\u{9}");
        assert!(!t.chars().any(is_unsafe_char));
    }

    #[test]
    fn doc_code_fences_backticks() {
        assert_eq!(doc_code("ee_link"), "`ee_link`");
        assert_eq!(doc_code("a`b"), "``a`b``");
        assert_eq!(doc_code("`x"), "`` `x ``");
        assert_eq!(doc_code("x\n<b>"), "`x\\u{a}<b>`");
    }

    #[test]
    fn identifier_parts_are_snake_case() {
        assert_eq!(identifier_part("ee_link"), "ee_link");
        assert_eq!(identifier_part("EE--Link 2"), "ee_link_2");
        assert_eq!(identifier_part("_\n}\nfn x() {\n"), "fn_x");
        assert_eq!(identifier_part("é"), "");
    }

    #[test]
    fn identifiers_and_keywords() {
        assert!(identifier("frame_pose_ee", "frame \"ee\"").is_ok());
        for bad in ["", "fn", "1a", "a-b", "é", "a b", "_"] {
            let e = identifier(bad, "frame \"x\"").unwrap_err();
            assert!(e.to_string().contains("frame \"x\""), "{e}");
        }
    }

    #[test]
    fn source_check_finds_what_escaped_nothing() {
        assert!(check_source("// a\n//\n", "// a\n//\nfn f() {}\n").is_ok());
        assert!(check_source("// a\nfn injected() {}\n", "").is_err());
        assert!(check_source("/// a\n", "").is_err());
        assert!(check_source("", "// a\u{2028}fn f() {}").is_err());
        assert!(check_source("", "const S: &str = \"\u{202e}\";").is_err());
    }
}
