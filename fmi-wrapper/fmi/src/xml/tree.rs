//! A serialised modelDescription as a plain element tree: read back from what fmi-schema
//! wrote, edited where fmi-schema 0.8 has no field for what the document must say (see
//! [`super::fmi2`] and [`super::fmi3`] for each edit and why), and written out indented, one
//! element per line, with hard-xml's escaping (the XML layer fmi-schema itself is built on).

use std::io::Write;

use hard_xml::XmlWriter;
use hard_xml::utils::xml_unescape;
use hard_xml::xmlparser::{ElementEnd, Token, Tokenizer};

/// Attributes holding `xs:double` numbers or lists of them (start values).
const NUMERIC: [&str; 10] = [
    "start",
    "min",
    "max",
    "nominal",
    "factor",
    "offset",
    "startTime",
    "stopTime",
    "stepSize",
    "tolerance",
];

/// An element: tag, attributes in order, children, and a comment written before it.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// Tag name.
    pub tag: String,
    /// Attributes, in the order they are written.
    pub attrs: Vec<(String, String)>,
    /// Child elements.
    pub children: Vec<Element>,
    /// `<!-- … -->` written on the line before the element (for readers of the file).
    pub comment: Option<String>,
}

impl Element {
    /// An element without attributes or children.
    pub fn new(tag: &str) -> Self {
        Self {
            tag: tag.into(),
            attrs: Vec::new(),
            children: Vec::new(),
            comment: None,
        }
    }

    /// Parses a document of elements and attributes (the declaration, comments and blank
    /// text are dropped; any other text is refused: modelDescription has none).
    pub fn parse(xml: &str) -> Result<Self, String> {
        let mut open: Vec<Element> = Vec::new();
        let mut root = None;
        for token in Tokenizer::from(xml) {
            match token.map_err(|e| e.to_string())? {
                Token::ElementStart { prefix, local, .. } => {
                    open.push(Element::new(&qualified(prefix.as_str(), local.as_str())))
                }
                Token::Attribute {
                    prefix,
                    local,
                    value,
                    ..
                } => {
                    let value = xml_unescape(value.as_str()).map_err(|e| e.to_string())?;
                    open.last_mut()
                        .ok_or("an attribute outside an element")?
                        .attrs
                        .push((qualified(prefix.as_str(), local.as_str()), value.into()));
                }
                Token::ElementEnd {
                    end: ElementEnd::Open,
                    ..
                } => {}
                Token::ElementEnd { .. } => {
                    let done = open.pop().ok_or("an element closed twice")?;
                    match open.last_mut() {
                        Some(parent) => parent.children.push(done),
                        None => root = Some(done),
                    }
                }
                Token::Text { text } if text.as_str().trim().is_empty() => {}
                Token::Declaration { .. } | Token::Comment { .. } => {}
                other => return Err(format!("unexpected {other:?}")),
            }
        }
        root.ok_or_else(|| "no root element".into())
    }

    /// The first child called `tag`.
    pub fn child_mut(&mut self, tag: &str) -> Option<&mut Element> {
        self.children.iter_mut().find(|c| c.tag == tag)
    }

    /// The value of attribute `key`.
    pub fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// Sets attribute `key` (replacing its value where it is already there).
    pub fn set(&mut self, key: &str, value: impl Into<String>) {
        let value = value.into();
        match self.attrs.iter_mut().find(|(k, _)| k == key) {
            Some((_, v)) => *v = value,
            None => self.attrs.push((key.into(), value)),
        }
    }

    /// Renames attribute `from` to `to`, where it is there.
    pub fn rename_attr(&mut self, from: &str, to: &str) {
        if let Some((k, _)) = self.attrs.iter_mut().find(|(k, _)| k == from) {
            *k = to.into();
        }
    }

    /// Spells infinities in numeric attributes as XML Schema does (`INF`, `-INF`): Rust's
    /// `Display`, which fmi-schema writes numbers with, spells them `inf`, which no `xs:double`
    /// reader accepts.
    pub fn spell_infinities(&mut self) {
        for (k, v) in &mut self.attrs {
            if NUMERIC.contains(&k.as_str()) && v.contains("inf") {
                let words: Vec<&str> = v
                    .split(' ')
                    .map(|w| match w {
                        "inf" => "INF",
                        "-inf" => "-INF",
                        w => w,
                    })
                    .collect();
                *v = words.join(" ");
            }
        }
        self.children.iter_mut().for_each(Element::spell_infinities);
    }

    /// The document: XML declaration, then the elements indented by two spaces a level.
    pub fn to_document(&self) -> Result<String, String> {
        let mut w = XmlWriter::new(Vec::with_capacity(256 * 1024));
        let io = |e: std::io::Error| e.to_string();
        writeln!(w.inner, r#"<?xml version="1.0" encoding="UTF-8"?>"#).map_err(io)?;
        self.write(&mut w, 0).map_err(io)?;
        String::from_utf8(w.into_inner()).map_err(|e| e.to_string())
    }

    fn write(&self, w: &mut XmlWriter<Vec<u8>>, depth: usize) -> std::io::Result<()> {
        let pad = "  ".repeat(depth);
        if let Some(c) = &self.comment {
            // Comments are ours (`index 7`); a `--` would end one early.
            writeln!(w.inner, "{pad}<!-- {} -->", c.replace("--", "- -"))?;
        }
        write!(w.inner, "{pad}")?;
        w.write_element_start(&self.tag)?;
        for (k, v) in &self.attrs {
            w.write_attribute(k, v)?;
        }
        if self.children.is_empty() {
            w.write_element_end_empty()?;
        } else {
            w.write_element_end_open()?;
            writeln!(w.inner)?;
            for c in &self.children {
                c.write(w, depth + 1)?;
            }
            write!(w.inner, "{pad}")?;
            w.write_element_end_close(&self.tag)?;
        }
        writeln!(w.inner)
    }
}

fn qualified(prefix: &str, local: &str) -> String {
    if prefix.is_empty() {
        local.into()
    } else {
        format!("{prefix}:{local}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_document_reads_back_as_written_with_escapes_and_infinities() {
        let mut doc = Element::new("a");
        doc.set("d", "x < y & \"z\"");
        doc.set("start", "1 inf -inf");
        let mut b = Element::new("b");
        b.comment = Some("index 1".into());
        doc.children.push(b);
        doc.spell_infinities();
        let text = doc.to_document().unwrap();
        assert!(text.contains(r#"start="1 INF -INF""#), "{text}");
        assert!(text.contains("  <!-- index 1 -->\n  <b/>\n"), "{text}");
        let mut back = Element::parse(&text).unwrap();
        back.children[0].comment = Some("index 1".into());
        assert_eq!(back, doc);
        assert_eq!(back.attr("d"), Some("x < y & \"z\""));
    }
}
