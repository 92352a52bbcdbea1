//! A small element tree over `quick-xml`: what the MAVLink reader needs of an XML document
//! (element names, attributes, the text inside an element, child elements in order).
//!
//! Comments, processing instructions and the declaration are dropped; entities are unescaped.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// An element: its name, attributes in document order, text and children.
#[derive(Debug, Default)]
pub struct Element {
    /// The tag name.
    pub name: String,
    /// The attributes, in document order.
    pub attrs: Vec<(String, String)>,
    /// The text directly inside the element (CDATA included), its pieces joined.
    pub text: String,
    /// The child elements, in document order.
    pub children: Vec<Element>,
}

impl Element {
    /// The value of attribute `name`.
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// The child elements named `name`.
    pub fn all<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Element> + 'a {
        self.children.iter().filter(move |c| c.name == name)
    }

    /// The first child element named `name`.
    pub fn first(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }
}

/// Parses a document into its root element.
///
/// # Errors
/// The text is not well-formed XML (the message says where), or has no root element.
pub fn parse(text: &str) -> Result<Element, String> {
    let mut reader = Reader::from_str(text);
    let mut stack: Vec<Element> = vec![Element::default()];
    loop {
        let at = reader.buffer_position();
        let event = reader
            .read_event()
            .map_err(|e| format!("XML error at byte {at}: {e}"))?;
        match event {
            Event::Start(start) => stack.push(open(&start)?),
            Event::Empty(start) => {
                let element = open(&start)?;
                top(&mut stack).children.push(element);
            }
            Event::End(_) => {
                let element = stack.pop().filter(|_| !stack.is_empty());
                let element = element.ok_or_else(|| format!("unbalanced end tag at byte {at}"))?;
                top(&mut stack).children.push(element);
            }
            Event::Text(t) => {
                let text = t
                    .decode()
                    .map_err(|e| format!("XML text at byte {at}: {e}"))?;
                let text = quick_xml::escape::unescape(&text)
                    .map_err(|e| format!("XML entity at byte {at}: {e}"))?;
                top(&mut stack).text.push_str(&text);
            }
            Event::GeneralRef(r) => {
                let name = r
                    .decode()
                    .map_err(|e| format!("XML reference at byte {at}: {e}"))?;
                let reference = format!("&{name};");
                let resolved = quick_xml::escape::unescape(&reference)
                    .map_err(|e| format!("XML entity at byte {at}: {e}"))?;
                top(&mut stack).text.push_str(&resolved);
            }
            Event::CData(c) => {
                top(&mut stack)
                    .text
                    .push_str(&String::from_utf8_lossy(c.as_ref()));
            }
            Event::Eof => break,
            _ => {}
        }
    }
    let mut document = stack.pop().filter(|_| stack.is_empty());
    document
        .as_mut()
        .and_then(|d| d.children.pop())
        .ok_or_else(|| "no root element (or an unclosed element)".to_string())
}

/// The element a start tag opens, with its attributes unescaped.
fn open(start: &BytesStart<'_>) -> Result<Element, String> {
    let name = String::from_utf8_lossy(start.name().as_ref()).into_owned();
    let mut attrs = Vec::new();
    for attr in start.attributes() {
        let attr = attr.map_err(|e| format!("attribute of <{name}>: {e}"))?;
        let key = String::from_utf8_lossy(attr.key.as_ref()).into_owned();
        let value = attr
            .normalized_value(quick_xml::XmlVersion::Explicit1_0)
            .map_err(|e| format!("attribute `{key}` of <{name}>: {e}"))?;
        attrs.push((key, value.into_owned()));
    }
    Ok(Element {
        name,
        attrs,
        ..Element::default()
    })
}

/// The element being filled: the stack always holds the document node at least.
fn top(stack: &mut [Element]) -> &mut Element {
    let last = stack.len() - 1;
    &mut stack[last]
}
