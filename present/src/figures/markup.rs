//! The HTML building blocks every report page shares (maud templates): the page shell
//! with its style sheet, inline SVG and figures. maud escapes every interpolated string;
//! SVG files enter as [`PreEscaped`] markup.

use maud::{DOCTYPE, Markup, PreEscaped, html};
use std::path::Path;

/// The reports' style sheet: compact tables that fit a 1366 px window, figures as small
/// multiples two to a row (`figure.wide`: full width).
pub const STYLE: &str = "body{font-family:sans-serif;margin:1.5em;max-width:1600px}table{border-collapse:collapse;margin-bottom:1em}td,th{border:1px solid #bbb;padding:3px 7px;text-align:right;white-space:nowrap;font-size:14px}th{background:#eee}td:first-child{text-align:left}h2.group{font-size:1.1em;margin:0.8em 0 0.3em}figure{display:inline-block;margin:0.5em;width:46%}figure.wide{width:96%}figure.panel{width:23.5%;margin:0.3em}figure.half{width:60%}figure svg,figure img{width:100%;height:auto}.card{border:1px solid #ccc;border-radius:4px;padding:0.3em 0.6em;margin:0.6em 0}.card h3{font-size:1em;margin:0.3em 0}.catbar{display:flex;width:100%;height:1.4em;font-size:12px;line-height:1.4em;color:#fff;overflow:hidden}.catbar span{white-space:nowrap;overflow:hidden;padding-left:3px;box-sizing:border-box}figcaption{font-size:13px}table.text td,table.text th{text-align:left;white-space:normal;max-width:26em}";

/// A whole self-contained page: `<title>` and `<h1>` both `title`, then `body`; the
/// returned text ends with a newline.
pub fn page(title: &str, body: Markup) -> String {
    let page = html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                title { (title) }
                style { (PreEscaped(STYLE)) }
            }
            body {
                h1 { (title) }
                (body)
            }
        }
    };
    page.into_string() + "\n"
}

/// An SVG file as inline markup: the XML prolog and namespace URIs dropped (inline SVG in
/// HTML needs neither, and the page then holds no URL at all).
pub fn inline_svg(svg: &Path) -> Result<Markup, String> {
    let text = std::fs::read_to_string(svg).map_err(|e| format!("{}: {e}", svg.display()))?;
    let body = text.find("<svg").map_or(text.as_str(), |i| &text[i..]);
    Ok(PreEscaped(
        body.replace(" xmlns=\"http://www.w3.org/2000/svg\"", "")
            .replace(" xmlns:xlink=\"http://www.w3.org/1999/xlink\"", ""),
    ))
}

/// A `<figure>` of `body` with `caption`; `class` (e.g. `wide`, `panel`, `half`) sets its
/// width in [`STYLE`].
pub fn figure(body: Markup, caption: &str, class: Option<&str>) -> Markup {
    html! {
        figure class=[class] { (body) figcaption { (caption) } }
    }
}

/// A figure file as a `<figure>`: the SVG inline, or its PNG sibling (`stem.png`) as a
/// base64 data URI when that is smaller (heat maps: thousands of SVG rectangles, a few kB
/// of PNG).
pub fn figure_file(svg: &Path, caption: &str, class: Option<&str>) -> Result<Markup, String> {
    use base64::Engine as _;
    let png = svg.with_extension("png");
    let svg_len = std::fs::metadata(svg)
        .map_err(|e| format!("{}: {e}", svg.display()))?
        .len();
    let png_len = std::fs::metadata(&png).map_or(u64::MAX, |m| m.len());
    let body = if png_len.saturating_mul(4) / 3 < svg_len {
        let bytes = std::fs::read(&png).map_err(|e| format!("{}: {e}", png.display()))?;
        let src = format!(
            "data:image/png;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(bytes)
        );
        html! { img alt=(caption) src=(src); }
    } else {
        inline_svg(svg)?
    };
    Ok(figure(body, caption, class))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_is_embedded_in_its_smaller_form() {
        let guard = tempfile::tempdir().unwrap();
        let dir = guard.path();
        let big_svg = format!("<svg>{}</svg>", "<rect/>".repeat(2000));
        // A heat map: large SVG, small PNG → the PNG as data, the caption escaped.
        std::fs::write(dir.join("heat.svg"), &big_svg).unwrap();
        std::fs::write(dir.join("heat.png"), [1u8, 2, 3]).unwrap();
        let m = figure_file(&dir.join("heat.svg"), "heat <map> & \"x\"", None)
            .unwrap()
            .into_string();
        assert!(
            m.contains(
                "<img alt=\"heat &lt;map&gt; &amp; &quot;x&quot;\" src=\"data:image/png;base64,AQID\">"
            ),
            "{m}"
        );
        assert!(m.contains("<figcaption>heat &lt;map&gt; &amp; &quot;x&quot;</figcaption>"));
        // A line chart: small SVG, large PNG → the SVG inline, unescaped, with its class.
        std::fs::write(dir.join("line.svg"), "<svg><path/></svg>").unwrap();
        std::fs::write(dir.join("line.png"), vec![0u8; 5000]).unwrap();
        let m = figure_file(&dir.join("line.svg"), "line", Some("panel"))
            .unwrap()
            .into_string();
        assert!(
            m.starts_with("<figure class=\"panel\"><svg><path/></svg>") && !m.contains("<img"),
            "{m}"
        );
        // No PNG beside it: the SVG.
        std::fs::write(dir.join("only.svg"), &big_svg).unwrap();
        assert!(
            figure_file(&dir.join("only.svg"), "x", None)
                .unwrap()
                .into_string()
                .contains("<svg>")
        );
    }

    #[test]
    fn a_page_escapes_its_title_and_keeps_its_body() {
        let p = page("a <b>", html! { p { "x" } });
        assert!(p.starts_with("<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"));
        assert!(p.contains("<title>a &lt;b&gt;</title>"));
        assert!(
            p.ends_with("<h1>a &lt;b&gt;</h1><p>x</p></body></html>\n"),
            "{p}"
        );
    }
}
