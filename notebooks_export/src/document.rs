//! A report as a list of sections, rendered to Markdown (`report.md`) and to a Jupyter notebook
//! (`report.ipynb`, see [`crate::notebook`]). Images are files next to the report.

/// One piece of a report.
#[derive(Clone, Debug, PartialEq)]
pub enum Block {
    /// Markdown text (a notebook cell of its own).
    Markdown(String),
    /// An image file in the report folder, with its alternative text; follows the previous
    /// Markdown in the same notebook cell.
    Image { file: String, alt: String },
    /// Python a student may run (the notebook stores it without outputs).
    Code(String),
}

/// A report: title and blocks in order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Document {
    pub title: String,
    pub blocks: Vec<Block>,
}

impl Document {
    pub fn new(title: &str) -> Self {
        Self {
            title: title.to_string(),
            blocks: Vec::new(),
        }
    }

    pub fn markdown(&mut self, text: impl Into<String>) -> &mut Self {
        self.blocks.push(Block::Markdown(text.into()));
        self
    }

    pub fn image(&mut self, file: &str, alt: &str) -> &mut Self {
        self.blocks.push(Block::Image {
            file: file.to_string(),
            alt: alt.to_string(),
        });
        self
    }

    pub fn code(&mut self, source: impl Into<String>) -> &mut Self {
        self.blocks.push(Block::Code(source.into()));
        self
    }

    /// The report as Markdown; images are linked by their relative file names.
    pub fn to_markdown(&self) -> String {
        let mut out = format!("# {}\n", self.title);
        for block in &self.blocks {
            out.push('\n');
            match block {
                Block::Markdown(text) => out.push_str(text.trim_end()),
                Block::Image { file, alt } => out.push_str(&format!("![{alt}]({file})")),
                Block::Code(source) => {
                    out.push_str(&format!("```python\n{}\n```", source.trim_end()))
                }
            }
            out.push('\n');
        }
        out
    }
}

/// A fenced block of TOML.
pub fn toml_block(text: &str) -> String {
    format!("```toml\n{}\n```", text.trim_end())
}
