//! Comments as Mitsuba's XML parser (pugixml) takes them: anything up to the first `-->`, where
//! strict XML forbids `--` inside a comment and a `-` before its end.

use std::borrow::Cow;

/// `text` with every comment's content made strict XML, byte for byte in place (so that the
/// parser's line and column numbers stay the file's): each `-` that follows a `-` of the
/// original inside a comment, and a `-` that ends one, becomes a space (a comment ends at the
/// first `-->`, so `x--->` is the content `x-`). CDATA sections are left alone. Text without
/// such comments is returned unchanged.
pub(crate) fn tolerate_dashes(text: &str) -> Cow<'_, str> {
    let mut bytes: Option<Vec<u8>> = None;
    let mut at = 0;
    let source = text.as_bytes();
    while let Some(start) = find(source, at, b"<") {
        let rest = &source[start..];
        if rest.starts_with(b"<![CDATA[") {
            at = find(source, start, b"]]>").map_or(source.len(), |end| end + 3);
            continue;
        }
        if !rest.starts_with(b"<!--") {
            at = start + 1;
            continue;
        }
        let content = start + 4;
        let Some(end) = find(source, content, b"-->") else {
            break;
        };
        for i in content..end {
            let after_dash = i > content && source[i - 1] == b'-';
            let ends_content = i + 1 == end;
            if source[i] == b'-' && (after_dash || ends_content) {
                bytes.get_or_insert_with(|| source.to_vec())[i] = b' ';
            }
        }
        at = end + 3;
    }
    match bytes {
        // Only ASCII dashes became ASCII spaces, so the text is still UTF-8.
        Some(bytes) => Cow::Owned(String::from_utf8(bytes).expect("dashes replaced by spaces")),
        None => Cow::Borrowed(text),
    }
}

/// The index of the first `needle` in `haystack` at or after `from`.
fn find(haystack: &[u8], from: usize, needle: &[u8]) -> Option<usize> {
    haystack
        .get(from..)?
        .windows(needle.len())
        .position(|w| w == needle)
        .map(|i| from + i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dashes_inside_comments_become_spaces_in_place() {
        let text = "<a><!-- run with --spp 4 ------ and -->\n<!--x--->\n<b/></a>";
        let strict = tolerate_dashes(text);
        assert_eq!(strict.len(), text.len());
        assert_eq!(
            strict,
            "<a><!-- run with - spp 4 -      and -->\n<!--x -->\n<b/></a>"
        );
        assert!(roxmltree::Document::parse(&strict).is_ok());
        assert!(roxmltree::Document::parse(text).is_err());
    }

    #[test]
    fn text_without_such_comments_is_borrowed_unchanged() {
        for text in [
            "<a>a -- b</a>",
            "<a><!-- fine - comment --></a>",
            "<a><![CDATA[<!-- -- -->]]></a>",
            "<a><!-- unterminated",
        ] {
            assert!(
                matches!(tolerate_dashes(text), Cow::Borrowed(t) if t == text),
                "{text}"
            );
        }
    }
}
