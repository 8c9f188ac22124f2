"""Plain SVG text for the pictures of a run (plot.py, leds.py, timeline.py):
a drawing of elements with attributes and children, written out as text,
the same bytes for the same drawing (as experiment/svg.py writes its own).

The drawing code builds it as it built svgwrite's (archived upstream):
`dwg.g()`, `dwg.line(start=, end=)`, `dwg.rect(insert=, size=)`,
`dwg.circle(center=, r=)`, `dwg.text(text, insert=)`, `dwg.polyline()`,
`dwg.polygon()`, `dwg.path(d=)`, `dwg.image(href=, insert=, size=)`,
`dwg.style()`, `element.add(child)`, `element.set_desc(title=)`,
`element.rotate(angle, center=)`, `dwg.tostring()`; a keyword `class_` or
`stroke_width` is the attribute `class` or `stroke-width`; attributes are
written sorted by name, numbers as Python prints them, and text escaped as
XML wants (the output is the one svgwrite gave)."""
from __future__ import annotations

_ATTRIBUTE = {"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "\n": "&#10;",
              "\r": "&#13;", "\t": "&#09;"}
_TEXT = {"&": "&amp;", "<": "&lt;", ">": "&gt;"}


def _escape(text: str, table: dict) -> str:
    if any(c in text for c in table):
        text = "".join(table.get(c, c) for c in text)
    return text


def _name(key: str) -> str:
    return key.rstrip("_").replace("_", "-")


def _value(value) -> str:
    return value if isinstance(value, str) else str(value)


class Element:
    """One SVG element: its attributes, its text and its children."""
    __slots__ = ("name", "attrs", "content", "children", "cdata")

    def __init__(self, name: str, text=None, **attrs):
        self.name = name
        self.attrs = {}
        self.content = None if text is None else str(text)
        self.children = []
        self.cdata = False
        for key, value in attrs.items():
            self[_name(key)] = value

    def __setitem__(self, key: str, value) -> None:
        self.attrs[key] = value

    def add(self, child: "Element") -> "Element":
        self.children.append(child)
        return child

    def rotate(self, angle, center=None) -> None:
        """Turned by `angle` degrees about `center` (a transform added)."""
        parts = [angle, *(center or ())]
        new = f"rotate({','.join(map(_value, parts))})"
        self["transform"] = f"{self.attrs.get('transform', '')} {new}".strip()

    def set_desc(self, title=None) -> None:
        """A tooltip: a `title` child, first."""
        if title is not None:
            self.children.insert(0, Element("title", title))

    def write(self, out: list) -> None:
        out.append(f"<{self.name}")
        for key in sorted(self.attrs):
            value = self.attrs[key]
            if value is None:
                continue
            value = _value(value)
            if value:
                out.append(f' {key}="{_escape(value, _ATTRIBUTE)}"')
        if self.content is None and not self.children:
            out.append(" />")
            return
        out.append(">")
        if self.content is not None:
            out.append(f"<![CDATA[{self.content}]]>" if self.cdata
                       else _escape(self.content, _TEXT))
        for child in self.children:
            child.write(out)
        out.append(f"</{self.name}>")


def _points(points) -> str:
    return " ".join(f"{x},{y}" for x, y in points)


class Drawing(Element):
    """The whole picture: an `svg` element of this size, with its `defs`,
    and the makers of the elements drawn in it."""
    __slots__ = ("defs",)

    def __init__(self, size: tuple, **attrs):
        super().__init__("svg", **attrs)
        self["width"], self["height"] = size
        self["version"], self["baseProfile"] = "1.1", "full"
        self["xmlns"] = "http://www.w3.org/2000/svg"
        self["xmlns:xlink"] = "http://www.w3.org/1999/xlink"
        self["xmlns:ev"] = "http://www.w3.org/2001/xml-events"
        self.defs = self.add(Element("defs"))

    def viewbox(self, minx, miny, width, height) -> None:
        self["viewBox"] = ",".join(map(_value, (minx, miny, width, height)))

    def tostring(self) -> str:
        out = []
        self.write(out)
        return "".join(out)

    # ---- the elements, as svgwrite's Drawing makes them ----------------------------

    @staticmethod
    def g(**attrs) -> Element:
        return Element("g", **attrs)

    @staticmethod
    def line(start, end, **attrs) -> Element:
        return Element("line", x1=start[0], y1=start[1], x2=end[0], y2=end[1], **attrs)

    @staticmethod
    def rect(insert, size, **attrs) -> Element:
        return Element("rect", x=insert[0], y=insert[1], width=size[0], height=size[1], **attrs)

    @staticmethod
    def circle(center, r, **attrs) -> Element:
        return Element("circle", cx=center[0], cy=center[1], r=r, **attrs)

    @staticmethod
    def text(text, insert, **attrs) -> Element:
        return Element("text", text, x=insert[0], y=insert[1], **attrs)

    @staticmethod
    def polyline(points, **attrs) -> Element:
        return Element("polyline", points=_points(points), **attrs)

    @staticmethod
    def polygon(points, **attrs) -> Element:
        return Element("polygon", points=_points(points), **attrs)

    @staticmethod
    def image(href, insert, size, **attrs) -> Element:
        element = Element("image", x=insert[0], y=insert[1], width=size[0], height=size[1],
                          **attrs)
        element["xlink:href"] = href
        return element

    @staticmethod
    def path(d, **attrs) -> Element:
        return Element("path", d=d, **attrs)

    @staticmethod
    def style(content: str) -> Element:
        element = Element("style", content, type="text/css")
        element.cdata = True
        return element
