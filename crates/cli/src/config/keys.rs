//! The texts made from the one key table ([`segmentation::KEYS`]): the
//! `[pipeline]` part of `sctl run --help`, the README's key table and the
//! keyword list of the Python stub's `segment`. The README and the stub
//! hold theirs between markers; the tests fail when either is stale and
//! rewrite both with `SCTL_WRITE_KEYS=1` (`SCTL_WRITE_KEYS=1 cargo test -p
//! sctl --lib config::keys`).

use segmentation::{Key, KeyType, Params, Stage, KEYS};
use std::fmt::Write as _;

/// The README's key table sits between these lines.
pub const README_BEGIN: &str =
    "<!-- key table: generated from segmentation::KEYS, see crates/cli/src/config/keys.rs -->";
/// The end of the README's key table.
pub const README_END: &str = "<!-- end of the key table -->";
/// The stub's keyword list sits between these lines.
pub const STUB_BEGIN: &str =
    "    # keys: generated from segmentation::KEYS, see crates/cli/src/config/keys.rs";
/// The end of the stub's keyword list.
pub const STUB_END: &str = "    # end of the keys";

/// The default of every key as TOML values ([`Params::default`]).
fn defaults() -> toml::Table {
    toml::Table::try_from(Params::default()).expect("the parameters serialise to a table")
}

/// The default of `key` as TOML text (`"five-point"`, `3000`, `0.2`).
pub fn default_toml(key: &Key) -> String {
    defaults()[key.name].to_string()
}

/// The `[pipeline]` lines of `sctl run --help`: one per key but the
/// reference-code variants, which one line names; `focal_file` after
/// `focal_solver`.
pub fn pipeline_help() -> String {
    let defaults = defaults();
    let mut out = String::new();
    for key in KEYS.iter().filter(|k| k.stage != Stage::ReferenceCode) {
        let head = format!("  {} = {}", key.name, defaults[key.name]);
        let what = match key.ty {
            KeyType::Choice | KeyType::SizeRule => format!("{}: {}", key.allowed, key.doc),
            _ => key.doc.to_string(),
        };
        let _ = writeln!(out, "{head:<30} {what}");
        if key.name == "focal_solver" {
            let _ = writeln!(
                out,
                "{:<30} focal_solver = \"external\": CSV of scene,hypothesis,f1,f2",
                "  focal_file = \"f{seed}.csv\""
            );
        }
    }
    let reference: Vec<&str> = KEYS
        .iter()
        .filter(|k| k.stage == Stage::ReferenceCode)
        .map(|k| k.name)
        .collect();
    let _ = writeln!(
        out,
        "  (and the reference code's variants, each defaulting to the thesis text:\n   {};\n   README.md, \"Parameter keys\", lists them)",
        reference.join(", ")
    );
    out
}

/// The README's key table (Markdown), without the markers.
pub fn readme_table() -> String {
    let defaults = defaults();
    let mut out = String::from(
        "| key | stage | type | default | values | what it does |\n|---|---|---|---|---|---|\n",
    );
    for key in KEYS {
        let ty = match key.ty {
            KeyType::Int => "integer",
            KeyType::Float => "number",
            KeyType::Bool => "bool",
            KeyType::Choice => "name",
            KeyType::WeightSets => "name or list",
            KeyType::SizeRule => "name or table",
        };
        let allowed = match key.ty {
            KeyType::Choice => key
                .allowed
                .split(" | ")
                .map(|v| format!("`{v}`"))
                .collect::<Vec<_>>()
                .join(" \\| "),
            _ if key.allowed.is_empty() => String::new(),
            _ => format!("`{}`", key.allowed.replace(" | ", "` \\| `")),
        };
        let _ = writeln!(
            out,
            "| `{}` | {} | {} | `{}` | {} | {} |",
            key.name,
            key.stage.name(),
            ty,
            defaults[key.name],
            allowed,
            key.doc.replace('|', "\\|")
        );
    }
    out
}

/// A TOML value as a Python literal.
fn python_literal(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => format!("{s:?}"),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => format!("{f:?}"),
        toml::Value::Boolean(b) => if *b { "True" } else { "False" }.to_string(),
        toml::Value::Array(items) => {
            let items: Vec<String> = items.iter().map(python_literal).collect();
            format!("[{}]", items.join(", "))
        }
        toml::Value::Table(table) => {
            let items: Vec<String> = table
                .iter()
                .map(|(k, v)| format!("{k:?}: {}", python_literal(v)))
                .collect();
            format!("{{{}}}", items.join(", "))
        }
        toml::Value::Datetime(d) => format!("{:?}", d.to_string()),
    }
}

/// The Python annotation of a key's values.
fn python_type(key: &Key) -> String {
    let names = |allowed: &str| {
        let quoted: Vec<String> = allowed
            .split(" | ")
            .filter(|v| !v.starts_with(['{', '[']))
            .map(|v| format!("{v:?}"))
            .collect();
        format!("Literal[{}]", quoted.join(", "))
    };
    match key.ty {
        KeyType::Int => "int".into(),
        KeyType::Float => "float".into(),
        KeyType::Bool => "bool".into(),
        KeyType::Choice => names(key.allowed),
        KeyType::WeightSets => format!("Union[{}, Sequence[Sequence[float]]]", names(key.allowed)),
        KeyType::SizeRule => format!("Union[{}, Dict[str, float]]", names(key.allowed)),
    }
}

/// The stub's keyword lines of `segment`, without the markers.
pub fn stub_keywords() -> String {
    let defaults = defaults();
    let mut out = String::new();
    for key in KEYS {
        let _ = writeln!(
            out,
            "    {}: {} = {},",
            key.name,
            python_type(key),
            python_literal(&defaults[key.name])
        );
    }
    out
}

/// `text` with the lines between the line `begin` and the line `end`
/// replaced by `body`; `None` when either marker is missing.
pub fn replace_block(text: &str, begin: &str, end: &str, body: &str) -> Option<String> {
    let start = text.find(&format!("{begin}\n"))? + begin.len() + 1;
    let stop = start + text[start..].find(&format!("{end}\n"))?;
    Some(format!("{}{body}{}", &text[..start], &text[stop..]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn repo_file(path: &str) -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path)
    }

    /// Checks the generated block of `path`; rewrites it when
    /// `SCTL_WRITE_KEYS` is set.
    fn check_block(path: &str, begin: &str, end: &str, body: &str) {
        let file = repo_file(path);
        let text = std::fs::read_to_string(&file).unwrap();
        let fresh = replace_block(&text, begin, end, body)
            .unwrap_or_else(|| panic!("{path}: the markers {begin:?} and {end:?} are missing"));
        if std::env::var_os("SCTL_WRITE_KEYS").is_some() {
            std::fs::write(&file, &fresh).unwrap();
        } else {
            assert!(
                fresh == text,
                "{path}: the key list is stale; rewrite it with \
                 SCTL_WRITE_KEYS=1 cargo test -p sctl --lib config::keys"
            );
        }
    }

    #[test]
    fn the_readme_key_table_is_the_generated_one() {
        check_block("README.md", README_BEGIN, README_END, &readme_table());
    }

    #[test]
    fn the_python_stub_keywords_are_the_generated_ones() {
        check_block(
            "python/sctl/__init__.pyi",
            STUB_BEGIN,
            STUB_END,
            &stub_keywords(),
        );
    }

    #[test]
    fn every_choice_lists_exactly_the_values_serde_reads() {
        for key in KEYS.iter().filter(|k| k.ty == KeyType::Choice) {
            for value in key.allowed.split(" | ") {
                let text = format!("{} = {value:?}", key.name);
                toml::from_str::<Params>(&text).unwrap_or_else(|e| panic!("{text}: {e}"));
            }
            // serde names every variant when it refuses one.
            let err = toml::from_str::<Params>(&format!("{} = \"?\"", key.name))
                .unwrap_err()
                .to_string();
            let expected = err.split("expected ").nth(1).unwrap_or("");
            let expected = expected.lines().next().unwrap_or("");
            let expected = expected.trim_start_matches("one of ");
            let mut variants: Vec<&str> = expected
                .split(", ")
                .flat_map(|v| v.split(" or "))
                .map(|v| v.trim().trim_matches('`'))
                .collect();
            let mut allowed: Vec<&str> = key.allowed.split(" | ").collect();
            variants.sort_unstable();
            allowed.sort_unstable();
            assert_eq!(allowed, variants, "{}: {err}", key.name);
        }
    }

    #[test]
    fn the_help_lists_at_most_25_pipeline_keys_and_names_the_rest() {
        let help = pipeline_help();
        let listed = help.lines().filter(|l| l.contains(" = ")).count();
        assert!(listed <= 25, "{listed} keys listed");
        for key in KEYS {
            assert!(
                help.contains(key.name),
                "{} missing from the help",
                key.name
            );
        }
        assert_eq!(
            default_toml(segmentation::key("method").unwrap()),
            "\"baseline\""
        );
    }

    #[test]
    fn python_literals_of_each_type() {
        let v: toml::Value = toml::from_str::<toml::Table>(
            "a = { relative-min = 0.02 }\nb = [[1.0, 2]]\nc = false\nd = \"x\"",
        )
        .unwrap()
        .into();
        let literal = |k: &str| python_literal(&v[k]);
        assert_eq!(literal("a"), "{\"relative-min\": 0.02}");
        assert_eq!(literal("b"), "[[1.0, 2]]");
        assert_eq!(
            (literal("c"), literal("d")),
            ("False".into(), "\"x\"".into())
        );
        assert_eq!(
            replace_block("a\nB\nold\nE\nz\n", "B", "E", "new\n").as_deref(),
            Some("a\nB\nnew\nE\nz\n")
        );
        assert_eq!(replace_block("a\n", "B", "E", ""), None);
    }
}
