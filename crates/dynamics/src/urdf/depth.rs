//! The nesting depth of an XML text's elements, measured before it is parsed: the XML parser
//! descends recursively, so a small file nested tens of thousands deep would overflow the stack.

use super::{err, MAX_XML_DEPTH};
use crate::error::Result;

/// Checks that no element of `text` lies more than [`MAX_XML_DEPTH`] elements deep. Comments,
/// CDATA sections, processing instructions and declarations are skipped, and `>` inside quoted
/// attribute values does not end a tag. Malformed markup is left to the parser to report.
///
/// # Errors
/// [`crate::DynamicsError::Urdf`] naming the limit and the byte offset where it is passed.
pub(super) fn check_depth(text: &str) -> Result<()> {
    let b = text.as_bytes();
    let find = |from: usize, pat: &[u8]| {
        (from <= b.len())
            .then(|| b[from..].windows(pat.len()).position(|w| w == pat))
            .flatten()
            .map(|k| from + k + pat.len())
    };
    let (mut i, mut depth) = (0, 0usize);
    while let Some(k) = b[i..].iter().position(|&c| c == b'<') {
        i += k;
        let rest = &b[i..];
        let skip_to = if rest.starts_with(b"<!--") {
            find(i + 4, b"-->")
        } else if rest.starts_with(b"<![CDATA[") {
            find(i + 9, b"]]>")
        } else if rest.starts_with(b"<?") {
            find(i + 2, b"?>")
        } else if rest.starts_with(b"<!") {
            find(i + 2, b">")
        } else if rest.starts_with(b"</") {
            depth = depth.saturating_sub(1);
            find(i + 2, b">")
        } else {
            let end = tag_end(b, i + 1);
            if end.is_some_and(|e| b[e - 2] != b'/') {
                depth += 1;
                if depth > MAX_XML_DEPTH {
                    return err(format!(
                        "elements nested more than {MAX_XML_DEPTH} deep (at byte {i})"
                    ));
                }
            }
            end
        };
        match skip_to {
            Some(j) => i = j,
            None => return Ok(()),
        }
    }
    Ok(())
}

/// The offset just past the `>` that ends the tag whose name starts at `from`, skipping quoted
/// attribute values.
fn tag_end(b: &[u8], from: usize) -> Option<usize> {
    let mut quote = None;
    for (k, &c) in b[from..].iter().enumerate() {
        match (quote, c) {
            (None, b'"' | b'\'') => quote = Some(c),
            (Some(q), _) if c == q => quote = None,
            (None, b'>') => return Some(from + k + 1),
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nested(d: usize) -> String {
        format!("<robot>{}{}</robot>", "<a>".repeat(d), "</a>".repeat(d))
    }

    #[test]
    fn the_depth_limit_refuses_deep_nesting_and_passes_real_markup() {
        assert!(check_depth(&nested(MAX_XML_DEPTH - 1)).is_ok());
        let e = check_depth(&nested(MAX_XML_DEPTH)).unwrap_err().to_string();
        assert!(e.contains("nested more than"), "{e}");
        // Self-closing tags, comments, CDATA, instructions and quoted `>` do not nest.
        let flat = format!(
            "<?xml version=\"1.0\"?><!-- <a><a> --><robot name=\"a>b\">{}<x><![CDATA[<a><a>]]></x></robot>",
            "<link name='l'/>".repeat(2 * MAX_XML_DEPTH)
        );
        assert!(check_depth(&flat).is_ok());
        // Unterminated markup is the parser's to report.
        assert!(check_depth("<robot><a").is_ok());
    }
}
