//! What Cargo cannot see of the workspace's structure, read from the sources: no two files of
//! a crate need each other (Cargo already refuses a cycle between crates), the crate graph
//! of the manifests is the one `docs/ARCHITECTURE.md` draws, and every folder is in the
//! README's layout table.
//!
//! A file depends on another when it names an item of it: a `use` of a `crate::`, `super::`,
//! `self::` or child-module path, or such a path in an expression. Paths are followed through
//! re-exports (`pub use`) to the file that defines the item; a re-export itself is a
//! module's facade, not a use, so a facade does not depend on the children it re-exports.
//! Comments and string literals are skipped.
//!
//! `cargo test --test module_graph -- --nocapture` prints the crate graph.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

type ModPath = Vec<String>;

/// The repository root (the facade crate's folder).
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every library crate of the workspace: its package name and its folder (the facade's is
/// the root), in name order.
fn crates() -> Vec<(String, PathBuf)> {
    let mut out = vec![("craterfield".to_owned(), root().to_path_buf())];
    for entry in fs::read_dir(root().join("crates")).expect("a crates folder") {
        let dir = entry.expect("a folder entry").path();
        let manifest = fs::read_to_string(dir.join("Cargo.toml")).expect("a crate manifest");
        out.push((package_name(&manifest), dir));
    }
    out.sort();
    out
}

/// The `name` of a manifest's `[package]`.
fn package_name(manifest: &str) -> String {
    manifest
        .lines()
        .find_map(|l| l.strip_prefix("name = \""))
        .and_then(|rest| rest.strip_suffix('"'))
        .expect("a package name")
        .to_owned()
}

/// The workspace crates a manifest depends on (`[dependencies]` only: tests may use more).
fn workspace_dependencies(manifest: &str) -> BTreeSet<String> {
    let mut section = "";
    let mut out = BTreeSet::new();
    for line in manifest.lines() {
        if line.starts_with('[') {
            section = line;
        } else if section == "[dependencies]" && line.starts_with("craterfield-") {
            out.insert(line.split([' ', '=']).next().unwrap_or_default().to_owned());
        }
    }
    out
}

/// The module path of a source file (`src/a/b.rs` and `src/a/b/mod.rs` are `a::b`).
fn module_of(rel: &Path) -> ModPath {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().expect("a file name");
    match last.as_str() {
        "lib.rs" | "mod.rs" => {}
        name => parts.push(name.trim_end_matches(".rs").to_owned()),
    }
    parts
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("readable source folder") {
        let path = entry.expect("a folder entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    PathSep,
    Open,
    Close,
    Comma,
    Semi,
    Star,
    Other,
}

/// Identifiers and the punctuation paths are made of; comments, strings and character
/// literals are dropped (they may hold `crate::` in prose or shader text).
fn tokenize(text: &str) -> Vec<Tok> {
    let b = text.as_bytes();
    let mut toks = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_whitespace() {
            i += 1;
        } else if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if c == b'/' && b.get(i + 1) == Some(&b'*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == b'r' && matches!(b.get(i + 1), Some(b'#') | Some(b'"')) && raw_start(b, i) {
            i = skip_raw_string(b, i);
        } else if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
        } else if c == b'\'' {
            i = skip_char_or_lifetime(b, i);
            toks.push(Tok::Other);
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                i += 1;
            }
            toks.push(Tok::Ident(text[start..i].to_owned()));
        } else if c.is_ascii_digit() {
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'.') {
                i += 1;
            }
            toks.push(Tok::Other);
        } else {
            i += 1;
            toks.push(match c {
                b':' if b.get(i) == Some(&b':') => {
                    i += 1;
                    Tok::PathSep
                }
                b'{' => Tok::Open,
                b'}' => Tok::Close,
                b',' => Tok::Comma,
                b';' => Tok::Semi,
                b'*' => Tok::Star,
                _ => Tok::Other,
            });
        }
    }
    toks
}

/// `r"` or `r#` that starts a raw string rather than ending an identifier.
fn raw_start(b: &[u8], i: usize) -> bool {
    i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')
}

fn skip_raw_string(b: &[u8], mut i: usize) -> usize {
    i += 1;
    let mut hashes = 0;
    while b.get(i) == Some(&b'#') {
        hashes += 1;
        i += 1;
    }
    if b.get(i) != Some(&b'"') {
        return i;
    }
    i += 1;
    while i < b.len() {
        if b[i] == b'"'
            && b[i + 1..]
                .iter()
                .take(hashes)
                .filter(|&&h| h == b'#')
                .count()
                == hashes
        {
            return i + 1 + hashes;
        }
        i += 1;
    }
    i
}

/// A character literal (`'x'`, `'\n'`, `'"'`) is skipped whole; a lifetime only its quote.
fn skip_char_or_lifetime(b: &[u8], i: usize) -> usize {
    if b.get(i + 1) == Some(&b'\\') {
        let mut j = i + 2;
        while j < b.len() && b[j] != b'\'' {
            j += 1;
        }
        return j + 1;
    }
    let ch_len = b.get(i + 1).map_or(1, |&c| utf8_len(c));
    if b.get(i + 1 + ch_len) == Some(&b'\'') {
        i + 2 + ch_len
    } else {
        i + 1
    }
}

fn utf8_len(first: u8) -> usize {
    match first {
        0xF0..=0xFF => 4,
        0xE0..=0xEF => 3,
        0xC0..=0xDF => 2,
        _ => 1,
    }
}

/// One leaf of a `use` tree: its path as written, and the name it binds (`None` for a glob).
#[derive(Debug, Clone)]
struct UseLeaf {
    path: Vec<String>,
    name: Option<String>,
}

/// Parses a use tree starting at `toks[i]`; returns the index after it.
fn parse_use_tree(toks: &[Tok], mut i: usize, prefix: &[String], out: &mut Vec<UseLeaf>) -> usize {
    let mut path = prefix.to_vec();
    loop {
        match toks.get(i) {
            Some(Tok::Ident(id)) => {
                path.push(id.clone());
                i += 1;
            }
            Some(Tok::Star) => {
                out.push(UseLeaf { path, name: None });
                return i + 1;
            }
            Some(Tok::Open) => {
                i += 1;
                while !matches!(toks.get(i), Some(Tok::Close) | None) {
                    i = parse_use_tree(toks, i, &path, out);
                    if toks.get(i) == Some(&Tok::Comma) {
                        i += 1;
                    }
                }
                return i + 1;
            }
            _ => return i,
        }
        match toks.get(i) {
            Some(Tok::PathSep) => i += 1,
            Some(Tok::Ident(kw)) if kw == "as" => {
                let alias = match toks.get(i + 1) {
                    Some(Tok::Ident(a)) => a.clone(),
                    _ => String::new(),
                };
                out.push(leaf(path, Some(alias)));
                return i + 2;
            }
            _ => {
                out.push(leaf(path, None));
                return i;
            }
        }
    }
}

fn leaf(mut path: Vec<String>, alias: Option<String>) -> UseLeaf {
    if path.last().is_some_and(|s| s == "self") {
        path.pop();
    }
    let name = alias.or_else(|| path.last().cloned());
    UseLeaf { path, name }
}

/// A path as written in module `here`, made absolute; `None` when it names something outside
/// the crate (a dependency, `std`, a local item).
fn absolute(path: &[String], here: &[String], modules: &BTreeSet<ModPath>) -> Option<ModPath> {
    let first = path.first()?;
    match first.as_str() {
        "crate" => Some(path[1..].to_vec()),
        "self" => Some([here, &path[1..]].concat()),
        "super" => {
            let mut base = here.to_vec();
            let mut rest = path;
            while rest.first().is_some_and(|s| s == "super") {
                base.pop()?;
                rest = &rest[1..];
            }
            Some([&base[..], rest].concat())
        }
        name => {
            let child = [here, &[name.to_owned()][..]].concat();
            modules.contains(&child).then(|| [here, path].concat())
        }
    }
}

struct Crate {
    /// Every module, from files and from inline `mod x { .. }` blocks.
    modules: BTreeSet<ModPath>,
    /// The file each module lives in.
    file_of: BTreeMap<ModPath, String>,
    /// `pub use` bindings per module: name to absolute target.
    reexports: BTreeMap<ModPath, BTreeMap<String, ModPath>>,
    /// Per file, the absolute paths it names.
    uses: BTreeMap<String, Vec<ModPath>>,
}

/// The uses of one file: each with the module it is written in.
struct FileScan {
    inline_modules: Vec<ModPath>,
    uses: Vec<(ModPath, UseLeaf, bool)>,
    bare_paths: Vec<(ModPath, Vec<String>)>,
}

fn scan(toks: &[Tok], file_module: &[String]) -> FileScan {
    let mut scan = FileScan {
        inline_modules: Vec::new(),
        uses: Vec::new(),
        bare_paths: Vec::new(),
    };
    let mut stack: Vec<(ModPath, usize)> = vec![(file_module.to_vec(), 0)];
    let mut depth = 0usize;
    let mut i = 0;
    while i < toks.len() {
        let here = stack.last().expect("the file's module").0.clone();
        match &toks[i] {
            Tok::Open => depth += 1,
            Tok::Close => {
                depth = depth.saturating_sub(1);
                if stack.len() > 1 && stack.last().is_some_and(|s| s.1 == depth) {
                    stack.pop();
                }
            }
            Tok::Ident(kw) if kw == "mod" => {
                if let (Some(Tok::Ident(name)), Some(Tok::Open)) =
                    (toks.get(i + 1), toks.get(i + 2))
                {
                    let inner = [&here[..], &[name.clone()][..]].concat();
                    scan.inline_modules.push(inner.clone());
                    stack.push((inner, depth));
                    depth += 1;
                    i += 3;
                    continue;
                }
            }
            Tok::Ident(kw) if kw == "use" => {
                let public = is_pub_before(toks, i);
                let mut leaves = Vec::new();
                i = parse_use_tree(toks, i + 1, &[], &mut leaves);
                for l in leaves {
                    scan.uses.push((here.clone(), l, public));
                }
                continue;
            }
            Tok::Ident(first)
                if matches!(first.as_str(), "crate" | "super" | "self")
                    && toks.get(i + 1) == Some(&Tok::PathSep)
                    && (i == 0 || toks[i - 1] != Tok::PathSep)
                    && !is_visibility_path(toks, i) =>
            {
                let mut path = vec![first.clone()];
                let mut j = i + 1;
                while toks.get(j) == Some(&Tok::PathSep) {
                    match toks.get(j + 1) {
                        Some(Tok::Ident(id)) => path.push(id.clone()),
                        _ => break,
                    }
                    j += 2;
                }
                scan.bare_paths.push((here, path));
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    scan
}

/// The path of a `pub(in path)` visibility, which names a module without using it.
fn is_visibility_path(toks: &[Tok], i: usize) -> bool {
    i >= 3
        && matches!(&toks[i - 1], Tok::Ident(kw) if kw == "in")
        && matches!(&toks[i - 3], Tok::Ident(kw) if kw == "pub")
}

/// `pub use`, `pub(crate) use`, `pub(super) use`.
fn is_pub_before(toks: &[Tok], i: usize) -> bool {
    let is = |k: usize, s: &str| matches!(toks.get(k), Some(Tok::Ident(id)) if id == s);
    (i >= 1 && is(i - 1, "pub")) || (i >= 4 && is(i - 4, "pub") && toks[i - 1] == Tok::Other)
}

fn read_crate(src: &Path) -> Crate {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files.sort();
    let mut krate = Crate {
        modules: BTreeSet::new(),
        file_of: BTreeMap::new(),
        reexports: BTreeMap::new(),
        uses: BTreeMap::new(),
    };
    let mut scans = Vec::new();
    for file in &files {
        let rel = file.strip_prefix(src).expect("under src");
        let name = rel.to_string_lossy().into_owned();
        let module = module_of(rel);
        krate.modules.insert(module.clone());
        krate.file_of.insert(module.clone(), name.clone());
        let text = fs::read_to_string(file).expect("readable source file");
        let s = scan(&tokenize(&text), &module);
        for m in &s.inline_modules {
            krate.modules.insert(m.clone());
            krate.file_of.insert(m.clone(), name.clone());
        }
        scans.push((name, s));
    }
    for (_, s) in &scans {
        for (here, l, public) in &s.uses {
            if let (true, Some(name), Some(abs)) =
                (*public, &l.name, absolute(&l.path, here, &krate.modules))
            {
                krate
                    .reexports
                    .entry(here.clone())
                    .or_default()
                    .insert(name.clone(), abs);
            }
        }
    }
    for (name, s) in scans {
        let mut paths = Vec::new();
        // A `pub use` is a module's facade, not a use of what it names.
        for (here, l, _) in s.uses.iter().filter(|u| !u.2) {
            paths.extend(absolute(&l.path, here, &krate.modules));
        }
        for (here, p) in &s.bare_paths {
            paths.extend(absolute(p, here, &krate.modules));
        }
        krate.uses.insert(name, paths);
    }
    krate
}

impl Crate {
    /// The file that defines what `path` names, through modules and re-exports.
    fn resolve(&self, path: &[String], depth: usize) -> String {
        let mut module: ModPath = Vec::new();
        for (k, seg) in path.iter().enumerate() {
            let child = [&module[..], &[seg.clone()][..]].concat();
            if self.modules.contains(&child) {
                module = child;
                continue;
            }
            let target = self.reexports.get(&module).and_then(|r| r.get(seg));
            match target {
                Some(t) if depth < 16 && t.as_slice() != path => {
                    return self.resolve(&[&t[..], &path[k + 1..]].concat(), depth + 1);
                }
                _ => break,
            }
        }
        self.file_of[&module].clone()
    }

    /// File-level edges: who names whom.
    fn file_edges(&self) -> BTreeMap<String, BTreeSet<String>> {
        let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (file, paths) in &self.uses {
            let out = edges.entry(file.clone()).or_default();
            for p in paths {
                let target = self.resolve(p, 0);
                if &target != file {
                    out.insert(target);
                }
            }
        }
        edges
    }
}

/// Strongly connected components with more than one node (Tarjan).
fn cycles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        s.on_stack.insert(v);
        let edges = s.edges;
        for w in edges.get(v).into_iter().flatten() {
            let w = w.as_str();
            if !s.index.contains_key(w) {
                visit(s, w);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).expect("visited");
                *lv = (*lv).min(lw);
            } else if s.on_stack.contains(w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).expect("visited");
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(w);
                comp.push(w.to_owned());
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                s.out.push(comp);
            }
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in edges.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    s.out
}

/// The edges behind a cycle, for the failure message.
fn explain(comp: &[String], edges: &BTreeMap<String, BTreeSet<String>>) -> String {
    let set: BTreeSet<&String> = comp.iter().collect();
    let mut lines = Vec::new();
    for a in comp {
        for b in edges.get(a).into_iter().flatten() {
            if set.contains(b) {
                lines.push(format!("    {a} -> {b}"));
            }
        }
    }
    lines.join("\n")
}

/// The reader itself: a re-exported item resolves to the file that defines it, comments and
/// strings are not read, and a test module's `super` is its file.
#[test]
fn the_reader_follows_reexports_and_skips_prose() {
    let toks =
        tokenize("// use crate::a::B;\nlet s = \"crate::c::D\"; use crate::e::{F, g::H as I};");
    let s = scan(&toks, &[]);
    let paths: Vec<String> = s.uses.iter().map(|(_, l, _)| l.path.join("::")).collect();
    assert_eq!(paths, ["crate::e::F", "crate::e::g::H"]);
    let toks = tokenize(
        "pub(in crate::a) struct S; mod tests { use super::*; fn f() { crate::x::y(); } }",
    );
    let s = scan(&toks, &["m".to_owned()]);
    assert_eq!(
        s.inline_modules,
        vec![vec!["m".to_owned(), "tests".to_owned()]]
    );
    assert_eq!(s.uses[0].0, vec!["m".to_owned(), "tests".to_owned()]);
    assert_eq!(s.bare_paths[0].1.join("::"), "crate::x::y");
    let krate = read_crate(&root().join("crates/render2d/src"));
    // `emit::TerrainEmitter` is defined in emit/terrain2d.rs and re-exported by emit/mod.rs.
    let target = krate.resolve(&["emit".to_owned(), "TerrainEmitter".to_owned()], 0);
    assert_eq!(target, "emit/terrain2d.rs");
}

/// No two files of a crate need each other, so every folder reads bottom-up.
#[test]
fn files_of_every_crate_form_no_cycle() {
    let mut report = Vec::new();
    for (name, dir) in crates() {
        let files = read_crate(&dir.join("src")).file_edges();
        for c in cycles(&files) {
            report.push(format!(
                "{name}: {}:\n{}",
                c.join(", "),
                explain(&c, &files)
            ));
        }
    }
    assert!(
        report.is_empty(),
        "files need each other:\n{}",
        report.join("\n")
    );
}

/// The crate table of `docs/ARCHITECTURE.md` has a row per crate whose last column names
/// exactly the workspace crates its manifest depends on.
#[test]
fn the_crate_graph_is_the_documented_one() {
    let architecture =
        fs::read_to_string(root().join("docs/ARCHITECTURE.md")).expect("docs/ARCHITECTURE.md");
    let mut wrong = Vec::new();
    for (name, dir) in crates() {
        let manifest = fs::read_to_string(dir.join("Cargo.toml")).expect("a manifest");
        let deps = workspace_dependencies(&manifest);
        println!(
            "{name:>22} -> {}",
            deps.iter().cloned().collect::<Vec<_>>().join(", ")
        );
        let start = format!("| `{name}` |");
        let Some(row) = architecture.lines().find(|l| l.starts_with(&start)) else {
            wrong.push(format!("{name}: no row in the crate table"));
            continue;
        };
        let uses = row
            .trim_end_matches('|')
            .rsplit('|')
            .next()
            .unwrap_or_default();
        let documented: BTreeSet<String> = uses
            .split('`')
            .skip(1)
            .step_by(2)
            .filter(|n| n.starts_with("craterfield"))
            .map(str::to_owned)
            .collect();
        if documented != deps {
            wrong.push(format!(
                "{name}: documented {documented:?}, manifest {deps:?}"
            ));
        }
    }
    assert!(
        wrong.is_empty(),
        "the crate table is wrong:\n{}",
        wrong.join("\n")
    );
}

/// Every crate folder and every folder of a crate's `src/` is in the README's layout table,
/// either on its own row or named in its parent's row.
#[test]
fn the_layout_table_matches_the_tree() {
    let readme = fs::read_to_string(root().join("README.md")).expect("README.md");
    let row = |path: &str| {
        let start = format!("| `{path}` |");
        readme
            .lines()
            .find(|l| l.starts_with(&start))
            .map(str::to_owned)
    };
    let mut missing = Vec::new();
    for (_, dir) in crates() {
        let rel = dir.strip_prefix(root()).expect("under the root");
        let base = if rel.as_os_str().is_empty() {
            "src".to_owned()
        } else {
            format!("{}", rel.display())
        };
        if row(&format!("{base}/")).is_none() {
            missing.push(format!("{base}/"));
        }
        let src = dir.join("src");
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        let mut folders = BTreeSet::new();
        for f in &files {
            let mut d = f.strip_prefix(&src).expect("under src").parent();
            while let Some(p) = d.filter(|p| !p.as_os_str().is_empty()) {
                folders.insert(p.to_string_lossy().into_owned());
                d = p.parent();
            }
        }
        let prefix = if base == "src" {
            base.clone()
        } else {
            format!("{base}/src")
        };
        for folder in &folders {
            let (parent, name) = match folder.rsplit_once('/') {
                Some((parent, name)) => (format!("{prefix}/{parent}/"), name),
                None => (format!("{base}/"), folder.as_str()),
            };
            let own = row(&format!("{prefix}/{folder}/")).is_some();
            let in_parent = row(&parent).is_some_and(|r| r.contains(&format!("`{name}/`")));
            if !own && !in_parent {
                missing.push(format!("{prefix}/{folder}/"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "not in the README's layout table:\n{}",
        missing.join("\n")
    );
}
