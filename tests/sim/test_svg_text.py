"""epuckc/sim/svg.py, the SVG text of the pictures: elements with sorted
attributes (`class_` is `class`, `stroke_width` is `stroke-width`), text and
attribute values escaped as XML wants, a tooltip title first, a style sheet
as CDATA; what it writes parses as SVG and reads back the same."""
import xml.etree.ElementTree as ET

from epuckc.sim.svg import Drawing

SVG = "{http://www.w3.org/2000/svg}"


def test_a_drawing_is_written_as_svg_text():
    dwg = Drawing(size=("120.0", "80.0"))
    dwg.viewbox(0, 0, 120.0, 80.0)
    dwg.defs.add(dwg.style(".a > b { fill: red }"))
    g = dwg.add(dwg.g(class_="robot-run", id="r1"))
    line = g.add(dwg.line(start=(1, 2.5), end=(3, 4), stroke="#222", stroke_width=1.5))
    line.set_desc(title='r1: 2 messages <"hi" & bye>')
    g.add(dwg.rect(insert=(0, 0), size=(10, 5), fill="white", empty="", skipped=None))
    box = g.add(dwg.rect(insert=(5, 5), size=(2, 2)))
    box.rotate(-30.0, center=(6.0, 6.0))
    g.add(dwg.circle(center=(4.0, 4.0), r=3))
    g.add(dwg.polyline([(0, 0), (1.5, 2)], fill="none"))
    g.add(dwg.polygon([(0, 0), (1, 0), (0, 1)]))
    g.add(dwg.path(d="M 0 0 L 1 1"))
    g.add(dwg.text("a < b & c", insert=(2.0, 3.0), font_family="sans-serif"))
    text = dwg.tostring()
    assert text.startswith('<svg baseProfile="full" height="80.0" version="1.1" '
                           'viewBox="0,0,120.0,80.0" width="120.0" '
                           'xmlns="http://www.w3.org/2000/svg" '
                           'xmlns:ev="http://www.w3.org/2001/xml-events" '
                           'xmlns:xlink="http://www.w3.org/1999/xlink"><defs>'
                           '<style type="text/css"><![CDATA[.a > b { fill: red }]]></style></defs>')
    assert ('<line stroke="#222" stroke-width="1.5" x1="1" x2="3" y1="2.5" y2="4">'
            '<title>r1: 2 messages &lt;"hi" &amp; bye&gt;</title></line>') in text
    assert '<rect fill="white" height="5" width="10" x="0" y="0" />' in text
    assert 'transform="rotate(-30.0,6.0,6.0)"' in text
    assert '<polyline fill="none" points="0,0 1.5,2" />' in text
    assert '<text font-family="sans-serif" x="2.0" y="3.0">a &lt; b &amp; c</text>' in text
    root = ET.fromstring(text)
    [group] = root.findall(f"{SVG}g")
    assert group.get("class") == "robot-run"
    assert [e.tag.removeprefix(SVG) for e in group] == ["line", "rect", "rect", "circle",
                                                         "polyline", "polygon", "path", "text"]
    assert group.find(f"{SVG}line/{SVG}title").text == 'r1: 2 messages <"hi" & bye>'
    assert group.find(f"{SVG}text").text == "a < b & c"


def test_attribute_values_keep_quotes_and_line_breaks():
    dwg = Drawing(size=(1, 1))
    dwg.add(dwg.g(data_note='say "x"\nthen\ty'))
    text = dwg.tostring()
    assert 'data-note="say &quot;x&quot;&#10;then&#09;y"' in text
    assert ET.fromstring(text).find(f"{SVG}g").get("data-note") == 'say "x"\nthen\ty'


def test_an_image_links_its_picture_as_svg_wants():
    dwg = Drawing(size=(10, 10))
    dwg.add(dwg.image(href="data:image/png;base64,AA==", insert=(1, 2), size=(3, 4),
                      class_="floor"))
    text = dwg.tostring()
    assert ('<image class="floor" height="4" width="3" x="1" '
            'xlink:href="data:image/png;base64,AA==" y="2" />') in text
    image = ET.fromstring(text).find(f"{SVG}image")
    assert image.get("{http://www.w3.org/1999/xlink}href") == "data:image/png;base64,AA=="


def test_every_element_the_drawing_code_makes_is_one_the_writer_has():
    """A picture's code asks `dwg.NAME(...)` of the writer: each NAME asked
    anywhere in epuckc is a maker the Drawing has (as `image` once was not)."""
    import re
    from pathlib import Path
    root = Path(__file__).resolve().parents[2] / "epuckc"
    asked = {m for path in root.rglob("*.py")
             for m in re.findall(r"\bdwg\.([a-z_]+)\(", path.read_text(encoding="utf-8"))}
    assert {"line", "image"} <= asked
    assert sorted(name for name in asked if not callable(getattr(Drawing, name, None))) == []
