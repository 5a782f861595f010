//! Jupyter notebook (nbformat 4.5) from a [`Document`]: Markdown cells with the images embedded
//! as cell attachments, so the notebook shows everything without running any code.

use std::path::Path;

use base64::Engine;
use serde_json::{Value, json};

use crate::document::{Block, Document};
use crate::error::{ReportError, read_text};

/// The MIME type of an image file, from its extension.
fn mime(file: &str) -> &'static str {
    match file
        .rsplit('.')
        .next()
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("gif") => "image/gif",
        Some("jpg" | "jpeg") => "image/jpeg",
        _ => "image/png",
    }
}

/// Notebook source: a list of lines, each but the last ending in `\n`.
fn source_lines(text: &str) -> Value {
    let lines: Vec<String> = text.split_inclusive('\n').map(String::from).collect();
    json!(lines)
}

/// Builds the notebook JSON; images are read from `dir` (the report folder).
pub fn to_notebook(doc: &Document, dir: &Path) -> Result<Value, ReportError> {
    let mut cells: Vec<Value> = Vec::new();
    let mut text = format!("# {}\n", doc.title);
    let mut attachments = serde_json::Map::new();
    let flush =
        |cells: &mut Vec<Value>, text: &mut String, att: &mut serde_json::Map<String, Value>| {
            if text.trim().is_empty() && att.is_empty() {
                return;
            }
            let mut cell = json!({
                "cell_type": "markdown",
                "id": format!("cell-{}", cells.len()),
                "metadata": {},
                "source": source_lines(text.trim_end()),
            });
            if !att.is_empty() {
                cell["attachments"] = Value::Object(std::mem::take(att));
            }
            cells.push(cell);
            text.clear();
        };
    for block in &doc.blocks {
        match block {
            Block::Markdown(md) => {
                flush(&mut cells, &mut text, &mut attachments);
                text.push_str(md.trim_end());
                text.push('\n');
            }
            Block::Image { file, alt } => {
                let path = dir.join(file);
                let bytes = std::fs::read(&path).map_err(|e| ReportError::io(&path, e))?;
                let name = file.replace(['/', '\\', ' '], "_");
                attachments.insert(
                    name.clone(),
                    json!({ mime(file): base64::engine::general_purpose::STANDARD.encode(bytes) }),
                );
                text.push_str(&format!("\n![{alt}](attachment:{name})\n"));
            }
            Block::Code(source) => {
                flush(&mut cells, &mut text, &mut attachments);
                cells.push(json!({
                    "cell_type": "code",
                    "id": format!("cell-{}", cells.len()),
                    "metadata": {},
                    "execution_count": null,
                    "outputs": [],
                    "source": source_lines(source.trim_end()),
                }));
            }
        }
    }
    flush(&mut cells, &mut text, &mut attachments);
    Ok(json!({
        "nbformat": 4,
        "nbformat_minor": 5,
        "metadata": {
            "kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"},
            "language_info": {"name": "python"},
            "fairgrasp": {"generator": concat!("fairgrasp-report ", env!("CARGO_PKG_VERSION"))},
        },
        "cells": cells,
    }))
}

/// Reads a notebook back (for tests and tools): its cells' types and joined sources.
pub fn read_cells(path: &Path) -> Result<Vec<(String, String)>, ReportError> {
    let v: Value = serde_json::from_str(&read_text(path)?)
        .map_err(|e| ReportError::malformed(path, format!("not JSON: {e}")))?;
    let cells = v["cells"]
        .as_array()
        .ok_or_else(|| ReportError::malformed(path, "no `cells` array"))?;
    Ok(cells
        .iter()
        .map(|c| {
            let source = c["source"]
                .as_array()
                .map(|l| l.iter().filter_map(Value::as_str).collect::<String>())
                .unwrap_or_default();
            (
                c["cell_type"].as_str().unwrap_or_default().to_string(),
                source,
            )
        })
        .collect())
}
