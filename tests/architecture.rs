//! The rules of README's "What is where", checked on the sources: which crate may depend on
//! which, that every file the `sweep` binary writes goes through `oblique-output`, and that the
//! solver's modules import each other without a cycle (docs/architecture.md).

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The names in the `[dependencies]` section of a Cargo.toml.
fn dependencies(manifest: &str) -> Vec<String> {
    let text = std::fs::read_to_string(root().join(manifest)).expect("read manifest");
    let mut deps = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            inside = line == "[dependencies]";
        } else if inside && !line.is_empty() && !line.starts_with('#') {
            let name = line.split(['=', '.', ' ']).next().unwrap_or("");
            deps.push(name.to_string());
        }
    }
    deps
}

#[test]
fn crates_depend_only_on_what_the_readme_allows() {
    let oblique = |d: &&String| d.starts_with("oblique-");
    for (manifest, allowed) in [
        ("crates/physics/Cargo.toml", &[][..]),
        ("crates/solver/Cargo.toml", &["oblique-physics"][..]),
        ("crates/output/Cargo.toml", &[][..]),
        (
            "crates/table/Cargo.toml",
            &["oblique-physics", "oblique-output"][..],
        ),
        (
            "crates/lookup/Cargo.toml",
            &["oblique-physics", "oblique-table"][..],
        ),
        ("crates/lookup-capi/Cargo.toml", &["oblique-lookup"][..]),
        ("crates/plot/Cargo.toml", &["oblique-output"][..]),
    ] {
        let deps = dependencies(manifest);
        let extra: Vec<_> = deps
            .iter()
            .filter(oblique)
            .filter(|d| !allowed.contains(&d.as_str()))
            .collect();
        assert!(extra.is_empty(), "{manifest} depends on {extra:?}");
    }
    // The pure crates do no I/O: no file formats, no output module.
    for manifest in ["crates/physics/Cargo.toml", "crates/solver/Cargo.toml"] {
        let deps = dependencies(manifest);
        assert!(
            deps.iter()
                .all(|d| ["serde", "thiserror", "oblique-physics"].contains(&d.as_str())),
            "{manifest}: {deps:?}"
        );
    }
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read folder") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_written_file_goes_through_the_output_module() {
    let mut files = Vec::new();
    sources(&root().join("src"), &mut files);
    for krate in std::fs::read_dir(root().join("crates")).expect("crates") {
        let src = krate.expect("entry").path().join("src");
        if src.is_dir() && !src.starts_with(root().join("crates/output")) {
            sources(&src, &mut files);
        }
    }
    // What writes a file itself, and why it may: each writes only at the path the output
    // module hands it (the temporary file), or is no output.
    let allowed = [
        ("crates/plot/src/lib.rs", "Backend::new(tmp,"),
        ("crates/plot/src/sheet/draw.rs", "Backend::new(tmp,"),
        // The seal goes into the temporary file before the module renames it.
        (
            "crates/table/src/write.rs",
            "OpenOptions::new().write(true).open(path)?",
        ),
        // A writability probe, created and removed at once.
        ("crates/sweep/src/job.rs", "std::fs::write(&probe"),
        // The built-in table's private scratch copy for HDF5 to open, created new in the
        // temporary folder and removed before returning: no output of the user's.
        ("crates/lookup/src/embedded.rs", "create_new("),
        ("crates/lookup/src/embedded.rs", "OpenOptions::new()"),
    ];
    let patterns = [
        "File::create",
        "fs::write(",
        "OpenOptions::new()",
        "create_new(",
        "BitMapBackend::new(",
        "SVGBackend::new(",
    ];
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).expect("read source");
        // Unit tests write their own fixtures.
        let code = text.split("#[cfg(test)]\nmod tests").next().unwrap_or("");
        let name = file.strip_prefix(root()).expect("in the repository");
        let name = name.to_string_lossy();
        for (n, line) in code.lines().enumerate() {
            let l = line.trim();
            if l.starts_with("//") || !patterns.iter().any(|p| l.contains(p)) {
                continue;
            }
            if !allowed.iter().any(|(f, s)| name == *f && l.contains(s)) {
                found.push(format!("{name}:{}: {l}", n + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "files written around oblique-output:\n  {}",
        found.join("\n  ")
    );
}

// ---------------------------------------------------------------------------------------------
// The import graph of a crate's modules.

use std::collections::{BTreeMap, BTreeSet};

/// The module a source file of `src/` holds: `lib.rs` the crate root (`""`), `foo.rs` and
/// `foo/mod.rs` → `foo`, `foo/bar.rs` → `foo::bar`.
fn module_of(file: &Path) -> String {
    let mut parts: Vec<String> = file
        .with_extension("")
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts.join("::")
}

/// `text` with its comments, string and character literals blanked (newlines kept, so line
/// numbers stay) and every item under `#[cfg(test)]` blanked too: doc links and unit tests
/// are no imports of the module.
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = b.clone();
    let blank = |out: &mut Vec<char>, from: usize, to: usize| {
        for c in &mut out[from..to.min(b.len())] {
            if *c != '\n' {
                *c = ' ';
            }
        }
    };
    let at = |i: usize, s: &str| s.chars().enumerate().all(|(k, c)| b.get(i + k) == Some(&c));
    let mut i = 0;
    while i < b.len() {
        if at(i, "//") {
            let end = (i..b.len()).find(|&j| b[j] == '\n').unwrap_or(b.len());
            blank(&mut out, i, end);
            i = end;
        } else if at(i, "/*") {
            let end = (i + 2..b.len())
                .find(|&j| at(j, "*/"))
                .map_or(b.len(), |j| j + 2);
            blank(&mut out, i, end);
            i = end;
        } else if b[i] == '"' {
            let mut j = i + 1;
            while j < b.len() && b[j] != '"' {
                j += if b[j] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i, j + 1);
            i = j + 1;
        } else if b[i] == '\'' && b.get(i + 1) == Some(&'\\') {
            let end = (i + 2..b.len())
                .find(|&j| b[j] == '\'')
                .map_or(b.len(), |j| j + 1);
            blank(&mut out, i, end);
            i = end;
        } else if b[i] == '\'' && b.get(i + 2) == Some(&'\'') {
            blank(&mut out, i, i + 3);
            i += 3;
        } else {
            i += 1; // also a lifetime's `'`
        }
    }
    // The item after `#[cfg(test)]`: up to its `;` or its closing brace.
    let attr: Vec<char> = "#[cfg(test)]".chars().collect();
    let mut i = 0;
    while i + attr.len() <= out.len() {
        if out[i..i + attr.len()] != attr[..] {
            i += 1;
            continue;
        }
        let (mut j, mut depth) = (i + attr.len(), 0);
        while j < out.len() {
            match out[j] {
                ';' if depth == 0 => break,
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        break;
                    }
                }
                _ => {}
            }
            j += 1;
        }
        for c in &mut out[i..(j + 1).min(b.len())] {
            if *c != '\n' {
                *c = ' ';
            }
        }
        i = j;
    }
    out.into_iter().collect()
}

/// A token of code: an identifier (with its line) or one punctuation character; `::` is one.
#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String, usize),
    Punct(&'static str),
}

fn tokens(code: &str) -> Vec<Tok> {
    let b: Vec<char> = code.chars().collect();
    let (mut out, mut i, mut line) = (Vec::new(), 0, 1);
    while i < b.len() {
        let c = b[i];
        if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_') {
                i += 1;
            }
            out.push(Tok::Ident(b[start..i].iter().collect(), line));
            continue;
        }
        if c == '\n' {
            line += 1;
        }
        let p = match c {
            ':' if b.get(i + 1) == Some(&':') => {
                i += 1;
                "::"
            }
            '{' => "{",
            '}' => "}",
            ',' => ",",
            ';' => ";",
            _ => " ",
        };
        if p != " " {
            out.push(Tok::Punct(p));
        }
        i += 1;
    }
    out
}

/// The paths that start at token `i` (`a::b::{c, d::e}` gives `a::b::c` and `a::b::d::e`),
/// and the index after them.
fn paths_at(toks: &[Tok], mut i: usize) -> (Vec<Vec<String>>, usize) {
    let mut prefix = Vec::new();
    loop {
        match toks.get(i) {
            Some(Tok::Ident(name, _)) => {
                prefix.push(name.clone());
                i += 1;
            }
            Some(Tok::Punct("{")) => {
                let mut all = Vec::new();
                i += 1;
                while i < toks.len() && toks[i] != Tok::Punct("}") {
                    if toks[i] == Tok::Punct(",") {
                        i += 1;
                        continue;
                    }
                    let (inner, next) = paths_at(toks, i);
                    all.extend(inner.into_iter().map(|p| [prefix.clone(), p].concat()));
                    i = next.max(i + 1);
                }
                return (all, i + 1);
            }
            _ => return (vec![prefix], i),
        }
        if toks.get(i) != Some(&Tok::Punct("::")) {
            return (vec![prefix], i);
        }
        i += 1;
    }
}

/// A crate's modules and, for each, the modules its code refers to (with the line of the
/// first reference).
struct Graph {
    edges: BTreeMap<String, BTreeMap<String, usize>>,
    /// Each module's file, under `src/`.
    files: BTreeMap<String, PathBuf>,
}

/// The import graph of the modules of one crate's `src/`, given as (path under `src/`, text).
///
/// An edge `a → b` is a path in `a`'s code (outside comments, strings and `#[cfg(test)]`
/// items) that names module `b`: `crate::…` (also `$crate::…` in macros), `super::…`,
/// `self::…`, or a path starting with one of `a`'s own child modules. A path names the longest
/// of its prefixes that is a module (`crate::foo::bar::X`: `foo::bar` if that file exists, else
/// `foo`); where that is the crate root and the root re-exports the next name (`pub use
/// foo::X;` in `lib.rs`), the module it re-exports from. A module's `mod child;` and its `pub
/// use` re-exports are no edges (a folder's `mod.rs` and `lib.rs` are the facade of their
/// children); children reaching their parent by `super::` are.
fn import_graph(files: &[(PathBuf, String)]) -> Graph {
    let modules: BTreeSet<String> = files.iter().map(|(p, _)| module_of(p)).collect();
    let split = |m: &str| -> Vec<String> {
        m.split("::")
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect()
    };
    let code: Vec<(String, Vec<Tok>)> = files
        .iter()
        .map(|(p, text)| (module_of(p), tokens(&code_only(text))))
        .collect();
    // The crate root's re-exports: a name to the path it stands for.
    let mut reexports: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (module, toks) in &code {
        if !module.is_empty() {
            continue;
        }
        for w in 0..toks.len() {
            if let (Tok::Ident(a, _), Some(Tok::Ident(b, _))) = (&toks[w], toks.get(w + 1)) {
                if a == "pub" && b == "use" {
                    for mut p in paths_at(toks, w + 2).0 {
                        if p.first().is_some_and(|h| h == "crate" || h == "self") {
                            p.remove(0);
                        }
                        if let Some(last) = p.last() {
                            reexports.insert(last.clone(), p.clone());
                        }
                    }
                }
            }
        }
    }
    let resolve = |base: Vec<String>, rest: &[String]| -> String {
        let full = [base.clone(), rest.to_vec()].concat();
        for n in (base.len()..=full.len()).rev() {
            let m = full[..n].join("::");
            if modules.contains(&m) {
                if n == 0 {
                    if let Some(target) = full.first().and_then(|name| reexports.get(name)) {
                        if let Some(k) = (1..target.len())
                            .rev()
                            .find(|&k| modules.contains(&target[..k].join("::")))
                        {
                            return target[..k].join("::");
                        }
                    }
                }
                return m;
            }
        }
        base.join("::")
    };
    let mut edges: BTreeMap<String, BTreeMap<String, usize>> = BTreeMap::new();
    for (module, toks) in &code {
        let me = split(module);
        let children: BTreeSet<String> = modules
            .iter()
            .map(|m| split(m))
            .filter(|m| m.len() == me.len() + 1 && m.starts_with(&me))
            .map(|m| m[me.len()].clone())
            .collect();
        let out = edges.entry(module.clone()).or_default();
        // Inline modules (`mod name { … }`) shift what `self` and `super` mean.
        let (mut inline, mut depth, mut opened): (Vec<usize>, usize, Vec<usize>) =
            (Vec::new(), 0, Vec::new());
        let mut pub_use = false;
        let mut i = 0;
        while i < toks.len() {
            match &toks[i] {
                Tok::Punct("{") => {
                    depth += 1;
                    i += 1;
                    continue;
                }
                Tok::Punct("}") => {
                    if opened.last() == Some(&depth) {
                        opened.pop();
                        inline.pop();
                    }
                    depth = depth.saturating_sub(1);
                    i += 1;
                    continue;
                }
                Tok::Punct(";") => {
                    pub_use = false;
                    i += 1;
                    continue;
                }
                _ => {}
            }
            let Tok::Ident(first, line) = &toks[i] else {
                i += 1;
                continue;
            };
            let prev = |k: usize| i.checked_sub(k).and_then(|j| toks.get(j));
            if first == "use" && matches!(prev(1), Some(Tok::Ident(p, _)) if p == "pub") {
                pub_use = true;
            }
            if first == "mod"
                && matches!(toks.get(i + 1), Some(Tok::Ident(..)))
                && toks.get(i + 2) == Some(&Tok::Punct("{"))
            {
                inline.push(0);
                opened.push(depth + 1);
            }
            if prev(1) == Some(&Tok::Punct("::")) || toks.get(i + 1) != Some(&Tok::Punct("::")) {
                i += 1;
                continue;
            }
            let (paths, next) = paths_at(toks, i);
            for path in paths {
                let mut base = [me.clone(), vec![String::new(); inline.len()]].concat();
                let mut rest = &path[..];
                match rest[0].as_str() {
                    "crate" => {
                        base.clear();
                        rest = &rest[1..];
                    }
                    "self" | "super" => {
                        while let Some(head) =
                            rest.first().filter(|h| *h == "self" || *h == "super")
                        {
                            if head == "super" {
                                base.pop();
                            }
                            rest = &rest[1..];
                        }
                    }
                    c if children.contains(c) && !pub_use => {}
                    _ => continue,
                }
                // Inside an inline module, still this file's module.
                base.truncate(base.len().min(me.len()));
                let target = resolve(base, rest);
                if target != *module {
                    out.entry(target).or_insert(*line);
                }
            }
            i = next.max(i + 1);
        }
    }
    let files = files
        .iter()
        .map(|(p, _)| (module_of(p), p.clone()))
        .collect();
    Graph { edges, files }
}

impl Graph {
    /// A cycle of modules (the first module again at its end), if there is one.
    fn cycle(&self) -> Option<Vec<String>> {
        fn visit(
            g: &Graph,
            m: &str,
            state: &mut BTreeMap<String, bool>,
            stack: &mut Vec<String>,
        ) -> Option<Vec<String>> {
            match state.get(m) {
                Some(true) => return None,
                Some(false) => {
                    let at = stack.iter().position(|s| s == m).expect("on the stack");
                    return Some([&stack[at..], &[m.to_string()]].concat());
                }
                None => {}
            }
            state.insert(m.to_string(), false);
            stack.push(m.to_string());
            for next in g.edges.get(m).into_iter().flat_map(|e| e.keys()) {
                if let Some(c) = visit(g, next, state, stack) {
                    return Some(c);
                }
            }
            stack.pop();
            state.insert(m.to_string(), true);
            None
        }
        let mut state = BTreeMap::new();
        self.edges
            .keys()
            .find_map(|m| visit(self, m, &mut state, &mut Vec::new()))
    }

    /// The cycle in words, each step with the line that makes it.
    fn explain(&self, cycle: &[String]) -> String {
        let name = |m: &str| {
            if m.is_empty() {
                "crate".to_string()
            } else {
                m.to_string()
            }
        };
        cycle
            .windows(2)
            .map(|w| {
                let line = self.edges[&w[0]][&w[1]];
                let file = self.files[&w[0]].display();
                format!("{} → {} ({file}:{line})", name(&w[0]), name(&w[1]))
            })
            .collect::<Vec<_>>()
            .join("\n  ")
    }
}

/// The files of a crate's `src/`: (path under `src/`, text).
fn crate_sources(krate: &str) -> Vec<(PathBuf, String)> {
    let src = root().join(krate).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    files.sort();
    files
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(&f).expect("read source");
            (f.strip_prefix(&src).expect("under src").to_path_buf(), text)
        })
        .collect()
}

fn assert_acyclic(krate: &str) {
    let graph = import_graph(&crate_sources(krate));
    if let Some(cycle) = graph.cycle() {
        panic!(
            "the modules of {krate}/src import each other in a cycle:\n  {}",
            graph.explain(&cycle)
        );
    }
}

#[test]
fn the_solver_modules_form_no_import_cycle() {
    assert_acyclic("crates/solver");
}

#[test]
fn the_import_graph_finds_a_cycle_where_there_is_one() {
    let file = |p: &str, t: &str| (PathBuf::from(p), t.to_string());
    let crate_of = |a: &str| {
        vec![
            file("lib.rs", "pub mod a;\npub mod b;\npub use b::c::Thing;\n"),
            file("a.rs", a),
            file("b/mod.rs", "pub mod c;\n/// [`crate::a`]\nfn f() {}\n"),
            file("b/c.rs", "use super::super::a::Item;\n"),
        ]
    };
    // Doc links, strings and unit tests are no edges; `mod c;` is none either.
    let quiet = "// crate::b::c\nconst S: &str = \"crate::b\";\n#[cfg(test)]\nmod tests { use crate::b::c::Thing; }\n";
    let g = import_graph(&crate_of(quiet));
    assert_eq!(g.cycle(), None, "{:?}", g.edges);
    assert_eq!(g.edges["b::c"].keys().collect::<Vec<_>>(), ["a"]);
    // A re-export of the root names the module it comes from; so does a grouped `use`.
    for a in [
        "use crate::Thing;\n",
        "fn f() -> crate::b::c::Thing { todo!() }\n",
        "use crate::{b::{c::Thing}};\n",
        "mod inner { use super::super::b::c; }\n",
    ] {
        let g = import_graph(&crate_of(a));
        let cycle = g.cycle().unwrap_or_else(|| panic!("{a}: {:?}", g.edges));
        assert_eq!(cycle.len(), 3, "{a}: {cycle:?}");
        assert!(
            g.explain(&cycle).contains("a → b::c"),
            "{a}: {}",
            g.explain(&cycle)
        );
    }
    // A child reaching its parent by `super::` is an edge, and so is the parent's use of it.
    let g = import_graph(&[
        file("lib.rs", "pub mod p;\n"),
        file("p/mod.rs", "mod k;\npub struct T;\nfn f() { k::g() }\n"),
        file("p/k.rs", "use super::T;\npub fn g() {}\n"),
    ]);
    assert_eq!(g.cycle(), Some(vec!["p".into(), "p::k".into(), "p".into()]));
}
