//! A small SVG writer: elements appended to a string, numbers rounded to 1/100 px.

use std::fmt::Write as _;

/// The font every figure asks for; [`crate::raster`] embeds it, so no system font is needed.
pub(crate) const FONT_FAMILY: &str = "DejaVu Sans";

/// An SVG document under construction. Coordinates are pixels, y pointing down.
pub(crate) struct Svg {
    out: String,
    open_groups: usize,
}

/// Appends `v` rounded to two decimals, without trailing zeros (`1.5`, `-3`, `0.25`).
pub(crate) fn push_num(out: &mut String, v: f64) {
    let r = (v * 100.0).round() / 100.0;
    // -0 prints as 0.
    let r = if r == 0.0 { 0.0 } else { r };
    if r == r.trunc() && r.abs() < 1e15 {
        let _ = write!(out, "{}", r as i64);
    } else {
        let start = out.len();
        let _ = write!(out, "{r:.2}");
        while out.ends_with('0') {
            out.pop();
        }
        if out.ends_with('.') {
            out.pop();
        }
        debug_assert!(out.len() > start);
    }
}

/// `v` as [`push_num`] writes it.
pub(crate) fn num(v: f64) -> String {
    let mut s = String::new();
    push_num(&mut s, v);
    s
}

/// Appends `text` with the five XML special characters escaped.
fn push_escaped(out: &mut String, text: &str) {
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // Control characters are not allowed in XML 1.0; drop them.
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
}

/// The `d` attribute of a `<path>`.
#[derive(Default)]
pub(crate) struct PathData {
    d: String,
}

impl PathData {
    pub(crate) fn new() -> Self {
        Self::default()
    }

    fn cmd(&mut self, c: char, x: f64, y: f64) -> &mut Self {
        if !self.d.is_empty() {
            self.d.push(' ');
        }
        self.d.push(c);
        push_num(&mut self.d, x);
        self.d.push(' ');
        push_num(&mut self.d, y);
        self
    }

    pub(crate) fn move_to(&mut self, x: f64, y: f64) -> &mut Self {
        self.cmd('M', x, y)
    }

    pub(crate) fn line_to(&mut self, x: f64, y: f64) -> &mut Self {
        self.cmd('L', x, y)
    }

    /// A circular arc of radius `r` from the current point to (x, y): the large one or the small
    /// one, clockwise on screen (`sweep`) or not.
    pub(crate) fn arc_to(&mut self, r: f64, large: bool, sweep: bool, x: f64, y: f64) -> &mut Self {
        if !self.d.is_empty() {
            self.d.push(' ');
        }
        self.d.push('A');
        push_num(&mut self.d, r);
        self.d.push(' ');
        push_num(&mut self.d, r);
        self.d.push_str(if large { " 0 1 " } else { " 0 0 " });
        self.d.push_str(if sweep { "1 " } else { "0 " });
        push_num(&mut self.d, x);
        self.d.push(' ');
        push_num(&mut self.d, y);
        self
    }

    pub(crate) fn close(&mut self) -> &mut Self {
        self.d.push('Z');
        self
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.d.is_empty()
    }

    pub(crate) fn as_str(&self) -> &str {
        &self.d
    }
}

impl Svg {
    /// A document of `width` × `height` pixels whose text uses [`FONT_FAMILY`].
    pub(crate) fn new(width: u32, height: u32) -> Self {
        let mut out = String::with_capacity(16 * 1024);
        let _ = writeln!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
             viewBox=\"0 0 {width} {height}\" font-family=\"{FONT_FAMILY}\">"
        );
        Self { out, open_groups: 0 }
    }

    /// An XML comment, for people reading the SVG.
    pub(crate) fn comment(&mut self, text: &str) {
        debug_assert!(!text.contains("--"));
        let _ = writeln!(self.out, "<!-- {text} -->");
    }

    /// Opens `<g attrs>`; close it with [`Svg::end_group`].
    pub(crate) fn group(&mut self, attrs: &str) {
        if attrs.is_empty() {
            self.out.push_str("<g>\n");
        } else {
            let _ = writeln!(self.out, "<g {attrs}>");
        }
        self.open_groups += 1;
    }

    pub(crate) fn end_group(&mut self) {
        debug_assert!(self.open_groups > 0);
        self.open_groups = self.open_groups.saturating_sub(1);
        self.out.push_str("</g>\n");
    }

    pub(crate) fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, attrs: &str) {
        self.out.push_str("<rect x=\"");
        push_num(&mut self.out, x);
        self.out.push_str("\" y=\"");
        push_num(&mut self.out, y);
        self.out.push_str("\" width=\"");
        push_num(&mut self.out, w.max(0.0));
        self.out.push_str("\" height=\"");
        push_num(&mut self.out, h.max(0.0));
        let _ = writeln!(self.out, "\" {attrs}/>");
    }

    pub(crate) fn circle(&mut self, cx: f64, cy: f64, r: f64, attrs: &str) {
        self.out.push_str("<circle cx=\"");
        push_num(&mut self.out, cx);
        self.out.push_str("\" cy=\"");
        push_num(&mut self.out, cy);
        self.out.push_str("\" r=\"");
        push_num(&mut self.out, r.max(0.0));
        let _ = writeln!(self.out, "\" {attrs}/>");
    }

    pub(crate) fn line(&mut self, x1: f64, y1: f64, x2: f64, y2: f64, attrs: &str) {
        self.out.push_str("<line x1=\"");
        push_num(&mut self.out, x1);
        self.out.push_str("\" y1=\"");
        push_num(&mut self.out, y1);
        self.out.push_str("\" x2=\"");
        push_num(&mut self.out, x2);
        self.out.push_str("\" y2=\"");
        push_num(&mut self.out, y2);
        let _ = writeln!(self.out, "\" {attrs}/>");
    }

    /// A `<path>`; nothing if `d` is empty.
    pub(crate) fn path(&mut self, d: &PathData, attrs: &str) {
        if d.is_empty() {
            return;
        }
        let _ = writeln!(self.out, "<path d=\"{}\" {attrs}/>", d.as_str());
    }

    /// `text` at (x, y) (the baseline; `attrs` may set `text-anchor`), escaped.
    pub(crate) fn text(&mut self, x: f64, y: f64, text: &str, attrs: &str) {
        self.out.push_str("<text x=\"");
        push_num(&mut self.out, x);
        self.out.push_str("\" y=\"");
        push_num(&mut self.out, y);
        let _ = write!(self.out, "\" {attrs}>");
        push_escaped(&mut self.out, text);
        self.out.push_str("</text>\n");
    }

    /// An `<image>` of `w` × `h` at `(x, y)` from `href` (a `data:` URL: no characters to escape).
    pub(crate) fn image(&mut self, x: f64, y: f64, w: f64, h: f64, href: &str) {
        debug_assert!(!href.contains(['"', '<', '&']));
        self.out.push_str("<image x=\"");
        push_num(&mut self.out, x);
        self.out.push_str("\" y=\"");
        push_num(&mut self.out, y);
        self.out.push_str("\" width=\"");
        push_num(&mut self.out, w);
        self.out.push_str("\" height=\"");
        push_num(&mut self.out, h);
        self.out.push_str("\" href=\"");
        self.out.push_str(href);
        self.out.push_str("\"/>\n");
    }

    /// A `<title>` (the tooltip of the element it sits in), escaped.
    pub(crate) fn title(&mut self, text: &str) {
        self.out.push_str("<title>");
        push_escaped(&mut self.out, text);
        self.out.push_str("</title>\n");
    }

    /// Closes any open group and the document.
    pub(crate) fn finish(mut self) -> String {
        for _ in 0..self.open_groups {
            self.out.push_str("</g>\n");
        }
        self.out.push_str("</svg>\n");
        self.out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        for (v, want) in [(1.0, "1"), (-0.001, "0"), (2.345, "2.35"), (0.5, "0.5"), (-12.1, "-12.1"), (1e20, "1e20")] {
            let got = num(v);
            if want == "1e20" {
                assert!(got.starts_with("1000000"), "{got}");
            } else {
                assert_eq!(got, want, "{v}");
            }
        }
    }

    #[test]
    fn text_is_escaped_and_groups_are_closed() {
        let mut s = Svg::new(20, 10);
        s.group("opacity=\"0.5\"");
        s.text(1.0, 2.0, "a<b & \"c\"\u{7}", "");
        let doc = s.finish();
        assert!(doc.contains(">a&lt;b &amp; &quot;c&quot;</text>"), "{doc}");
        assert!(doc.ends_with("</g>\n</svg>\n"));
        assert!(doc.contains("width=\"20\" height=\"10\""));
    }

    #[test]
    fn path_data() {
        let mut d = PathData::new();
        d.move_to(0.0, 0.0).line_to(1.256, 2.0);
        d.arc_to(5.0, true, false, 3.0, 4.0).close();
        assert_eq!(d.as_str(), "M0 0 L1.26 2 A5 5 0 1 0 3 4Z");
    }
}
