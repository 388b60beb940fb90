//! The `quick_xml::Writer` the MJCF, SDF and URDF exports write through: indented by two
//! spaces, a newline at the end, and the two things those files do that the writer's own
//! indentation does not: a run of elements kept on one line, and the title as a comment.

use std::io;

use quick_xml::Writer;
use quick_xml::escape::escape;
use quick_xml::events::{BytesDecl, BytesText, Event};

/// A writer into memory, indenting by two spaces.
pub(super) type XmlWriter = Writer<Vec<u8>>;

/// The document `write` makes, ending with a newline.
pub(super) fn document(write: impl FnOnce(&mut XmlWriter) -> io::Result<()>) -> String {
    let mut xml = Writer::new_with_indent(Vec::new(), b' ', 2);
    write(&mut xml).expect("writing to memory cannot fail");
    let mut out = String::from_utf8(xml.into_inner()).expect("quick_xml writes the UTF-8 given");
    out.push('\n');
    out
}

/// `<?xml version="1.0"?>`.
pub(super) fn declaration(xml: &mut XmlWriter) -> io::Result<()> {
    xml.write_event(Event::Decl(BytesDecl::new("1.0", None, None)))
}

/// `<!-- title -->`, escaped, with no `--` inside (which XML forbids in a comment).
pub(super) fn title_comment(xml: &mut XmlWriter, title: &str) -> io::Result<()> {
    let text = format!(" {} ", escape(title).replace("--", "- -"));
    xml.write_event(Event::Comment(BytesText::from_escaped(text)))
}

/// The next tag follows on the same line (the writer breaks the line before every tag
/// that does not follow text: an empty text stands in).
pub(super) fn same_line(xml: &mut XmlWriter) -> io::Result<()> {
    xml.write_event(Event::Text(BytesText::new("")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_are_escaped_without_double_hyphens_and_same_line_keeps_the_line() {
        let text = document(|xml| {
            declaration(xml)?;
            title_comment(xml, "a<b & \"c\" -- d")?;
            xml.create_element("a").write_inner_content(|xml| {
                xml.create_element("b").write_empty()?;
                same_line(xml)?;
                xml.create_element("c").write_empty()?;
                Ok(())
            })?;
            Ok(())
        });
        assert_eq!(
            text,
            "<?xml version=\"1.0\"?>\n<!-- a&lt;b &amp; &quot;c&quot; - - d -->\n<a>\n  <b/><c/>\n</a>\n"
        );
    }
}
