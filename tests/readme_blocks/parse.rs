//! The fenced blocks of a Markdown file, each with its section and what the text prints
//! after it.

/// The languages of the blocks a reader runs: shell lines and Python.
pub(super) const COMMAND_LANGUAGES: [&str; 4] = ["sh", "bash", "console", "python"];

/// A fenced block of a Markdown file.
pub(super) struct Block {
    /// The file's name, for messages.
    pub(super) file: &'static str,
    /// The line of its opening fence, from 1.
    pub(super) line: usize,
    /// The heading of the section it is in.
    pub(super) heading: String,
    /// What follows the opening fence: `sh`, `python`, `text`...
    pub(super) language: String,
    /// Its lines, without the fences and the fence's indentation.
    pub(super) text: String,
    /// Everything after it up to the next command block or heading: the prose and the
    /// printed output that describe what it gave.
    pub(super) after: String,
    /// Everything after it up to the next heading, other blocks included: where the
    /// figures of what it gave may be printed (a map's table after a block of shards).
    pub(super) section_rest: String,
}

impl Block {
    /// Whether a reader runs it (shell or Python), as against output, TOML or Rust.
    pub(super) fn is_command(&self) -> bool {
        COMMAND_LANGUAGES.contains(&self.language.as_str())
    }

    /// Where it is, for messages: `README.md:612 (### Sizing the gear ...)`.
    pub(super) fn place(&self) -> String {
        format!("{}:{} ({})", self.file, self.line, self.heading)
    }

    /// The `text` blocks within what follows it: the output it printed.
    pub(super) fn printed_output(&self) -> Vec<String> {
        let mut out = Vec::new();
        let mut current: Option<String> = None;
        for line in self.after.lines() {
            let fence = line.trim_start();
            match (&mut current, fence.strip_prefix("```")) {
                (None, Some("text")) => current = Some(String::new()),
                (Some(text), Some("")) => {
                    out.push(std::mem::take(text));
                    current = None;
                }
                (Some(text), _) => {
                    text.push_str(line.trim_end());
                    text.push('\n');
                }
                (None, _) => {}
            }
        }
        out
    }
}

/// The fenced blocks of `markdown`, in order.
pub(super) fn blocks(file: &'static str, markdown: &str) -> Vec<Block> {
    let lines: Vec<&str> = markdown.lines().collect();
    let mut blocks = Vec::new();
    let mut heading = String::from("(top)");
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let trimmed = line.trim_start();
        if let Some(language) = trimmed.strip_prefix("```") {
            let indent = line.len() - trimmed.len();
            let end = (i + 1..lines.len())
                .find(|&j| lines[j].trim() == "```")
                .unwrap_or_else(|| panic!("{file}:{}: a fence that is never closed", i + 1));
            let text: Vec<&str> = lines[i + 1..end]
                .iter()
                .map(|l| l.get(indent..).unwrap_or(l.trim_start()))
                .collect();
            blocks.push(Block {
                file,
                line: i + 1,
                heading: heading.clone(),
                language: language.trim().to_string(),
                text: text.join("\n") + "\n",
                after: after(&lines[end + 1..], true),
                section_rest: after(&lines[end + 1..], false),
            });
            i = end + 1;
            continue;
        }
        if trimmed.starts_with('#') {
            heading = trimmed.to_string();
        }
        i += 1;
    }
    blocks
}

/// The lines of `rest` up to the next heading outside a fence, or to the next command block
/// if `to_next_block`.
fn after(rest: &[&str], to_next_block: bool) -> String {
    let mut out = String::new();
    let mut in_fence = false;
    for line in rest {
        let trimmed = line.trim_start();
        if let Some(language) = trimmed.strip_prefix("```") {
            if to_next_block && !in_fence && COMMAND_LANGUAGES.contains(&language.trim()) {
                break;
            }
            in_fence = !in_fence;
        } else if !in_fence && trimmed.starts_with('#') {
            break;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}
