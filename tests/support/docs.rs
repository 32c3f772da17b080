//! Reading the docs as the docs tests do: which files are the docs, and their fenced blocks.

use std::path::Path;

/// README.md, CONTRIBUTING.md and every chapter of docs/ (not docs/upstream/: issue texts
/// written for others), as (path from the root, text).
pub fn docs(root: &Path) -> Vec<(String, String)> {
    let mut chapters: Vec<String> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    chapters.sort();
    let names = ["README.md", "CONTRIBUTING.md"].map(String::from).into_iter().chain(chapters);
    names.map(|n| (n.clone(), std::fs::read_to_string(root.join(&n)).unwrap())).collect()
}

/// One fenced block: its info string, its text, and its first line's number.
pub struct Block {
    pub info: String,
    pub text: String,
    pub line: usize,
}

/// The fenced blocks of `markdown`, and its prose with the blocks left out.
pub fn fenced(markdown: &str) -> (Vec<Block>, String) {
    let (mut blocks, mut prose, mut open) = (Vec::new(), String::new(), None::<Block>);
    for (i, line) in markdown.lines().enumerate() {
        match (open.as_mut(), line.trim_start().strip_prefix("```")) {
            (None, Some(info)) => {
                open = Some(Block { info: info.trim().to_string(), text: String::new(), line: i + 1 })
            }
            (Some(_), Some("")) => blocks.extend(open.take()),
            (Some(block), _) => block.text.push_str(&(line.to_string() + "\n")),
            (None, None) => prose.push_str(&(line.to_string() + "\n")),
        }
    }
    assert!(open.is_none(), "a fenced block is never closed");
    (blocks, prose)
}
