"""The report as one document model, rendered to Markdown (REPORT.md) and to HTML (report/index.html).

report.py builds the document once from the data: headings, paragraphs, tables, figures, lists,
links. The two renderers here walk it, so both formats carry the same text, cells and images.
What only one format can show is a node kind or an attribute that the other renders its plainer
way: a Details block (HTML <details>) is in Markdown its title as a heading and its body; a More
text (a long reason collapsed after its start) is in Markdown the whole text; a Media whose file is
absent is a labelled placeholder in both; classes, ids and titles are HTML attributes only; a
Table's merged columns are one cell across a run of rows on the page (rowspan), the cell in every
row in Markdown; Cards (the matrices' rows) are blocks with images on the page, a table row each in
Markdown, from the same values; Raw carries a piece already written for each format (another
module's section, the comparison widget).

Inline content is a str, an inline node, or a list of them. File paths are relative to the results
folder: Markdown links them as they are, the page (one folder down) through "../"; a link to
"#anchor" stays as it is.
"""
import html

MD, HTML = "md", "html"


def esc(x):
    return html.escape(str(x), quote=True)


class Node:
    """A node: its fields as keyword arguments (those not given are None)."""
    fields = ()

    def __init__(self, *args, **kw):
        for name, value in zip(self.fields, args):
            setattr(self, name, value)
        for name in self.fields[len(args):]:
            setattr(self, name, kw.pop(name, None))
        if kw:
            raise TypeError(f"{type(self).__name__}: unknown fields {sorted(kw)}")


# ---- inline nodes ---------------------------------------------------------------------------------

class Link(Node):
    """md_href: Markdown's target where it differs (an anchor only the page has)."""
    fields = ("text", "href", "md_href")


class Strong(Node):
    fields = ("content",)


class Em(Node):
    fields = ("content",)


class Code(Node):
    fields = ("content",)


class Span(Node):
    """Text with an HTML class or title (Markdown: the text); block=True makes it a <div>."""
    fields = ("content", "cls", "title", "block")


class More(Node):
    """A long text whose start shows and whose rest opens on a click (Markdown: the whole text)."""
    fields = ("text", "keep", "summary")


class Media(Node):
    """An image, or where its file is absent (exists False) a labelled placeholder naming it.
    attrs: the <img>'s extra attributes; md_link: Markdown links the file under this word
    instead of showing it."""
    fields = ("src", "caption", "exists", "attrs", "md_link")


# ---- block nodes ----------------------------------------------------------------------------------

class Heading(Node):
    fields = ("level", "content", "id")


class Para(Node):
    fields = ("content", "cls")


class Bullets(Node):
    fields = ("items",)


class Cell(Node):
    """A table cell; header=True makes it a <th>."""
    fields = ("content", "cls", "title", "header")


class Row(Node):
    """A table row; attrs: the <tr>'s attributes besides its class."""
    fields = ("cells", "cls", "attrs")


class GroupRow(Node):
    """A row naming the group of rows after it: in HTML one header cell across the table, in
    Markdown a heading (at md_level) that starts a table of its own."""
    fields = ("content", "cls", "md_level")


class Table(Node):
    """head: the header cells (Cell or inline content); rows: Row or GroupRow. merge: the indices of
    columns whose repeated cells are merged: where a cell repeats the one above it (and so does every
    merged column before it), the page shows one cell across the run (rowspan); Markdown writes the
    cell in every row."""
    fields = ("head", "rows", "id", "cls", "merge")


class Figure(Node):
    fields = ("src", "caption", "cls")


class Box(Node):
    """A <div> (or tag) around blocks, for layout; Markdown renders the blocks only."""
    fields = ("children", "cls", "id", "tag")


class Details(Node):
    """A collapsed block: HTML <details> with its summary; Markdown its md_title (else the summary)
    as a heading at md_level (0: no heading), then the body."""
    fields = ("summary", "children", "cls", "id", "md_title", "md_level")


class Card(Node):
    """One item of Cards. keys: its naming parts (inline); status: a word; notes: inline (Span)
    lines; values: (label, value) pairs; figures: Figure, or inline content (a note where none is)."""
    fields = ("keys", "status", "notes", "values", "figures", "cls")


class Cards(Node):
    """Items of one kind, the same content in both formats, laid out differently. On the page each
    Card is a block <div class=cls>: its keys joined by " · " and its status as an <h4>, its notes,
    its values as a <dl>, its figures side by side. In Markdown one table, a row per Card: a column
    per key (key_head names them), the status, the notes (notes_head), a column per value label
    (every label any card has, in order; empty where a card lacks it), the figures as links
    (figures_head)."""
    fields = ("cards", "key_head", "notes_head", "figures_head")


class Only(Node):
    """Blocks that one format shows and the other has no place for (the page's navigation)."""
    fields = ("fmt", "children")


class Raw(Node):
    """A piece written for each format: html a string, md a list of lines."""
    fields = ("html", "md")


def _items(content):
    if content is None:
        return []
    return content if isinstance(content, (list, tuple)) else [content]


# ---- Markdown -------------------------------------------------------------------------------------

def md_cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


class MarkdownRenderer:
    """Blocks to lines of Markdown; blocks are separated by one blank line."""

    def inline(self, content):
        return "".join(self.one(x) for x in _items(content))

    def one(self, x):
        if isinstance(x, str):
            return x
        if isinstance(x, Link):
            return f"[{self.inline(x.text)}]({x.md_href or x.href})"
        if isinstance(x, Strong):
            return f"**{self.inline(x.content)}**"
        if isinstance(x, Em):
            return f"*{self.inline(x.content)}*"
        if isinstance(x, Code):
            return self.inline(x.content)
        if isinstance(x, Span):
            return (" " if x.block else "") + self.inline(x.content)
        if isinstance(x, More):
            return f" ({x.summary}: {x.text})" if x.summary is not None else x.text
        if isinstance(x, Media):
            if not x.exists:
                return f"*{x.caption}: not written here*"
            if x.md_link:
                return f"[{x.md_link}]({x.src})"
            return f"![{x.caption}]({x.src})"
        if isinstance(x, Raw):
            return " ".join(x.md)
        raise TypeError(f"not inline: {x!r}")

    def blocks(self, nodes):
        out = []
        for n in _items(nodes):
            lines = self.block(n)
            if lines:
                out += ([""] if out and out[-1] != "" else []) + lines
        return out

    def block(self, n):
        if isinstance(n, Heading):
            return ["#" * n.level + " " + self.inline(n.content)]
        if isinstance(n, Para):
            return [self.inline(n.content)]
        if isinstance(n, Bullets):
            return [f"- {self.inline(x)}" for x in n.items]
        if isinstance(n, Table):
            return self.table(n)
        if isinstance(n, Figure):
            return [f"![{n.caption}]({n.src})"]
        if isinstance(n, Box):
            return self.blocks(n.children)
        if isinstance(n, Details):
            if n.md_level == 0:
                return self.blocks(n.children)
            title = n.md_title if n.md_title is not None else n.summary
            return self.blocks([Heading(n.md_level or 3, title)] + _items(n.children))
        if isinstance(n, Cards):
            return self.cards(n)
        if isinstance(n, Only):
            return self.blocks(n.children) if n.fmt == MD else []
        if isinstance(n, Raw):
            return list(n.md)
        raise TypeError(f"not a block: {n!r}")

    def cells(self, cells):
        return "| " + " | ".join(md_cell(self.inline(c.content if isinstance(c, Cell) else c).strip())
                                 for c in cells) + " |"

    def table(self, t):
        head = [self.cells(t.head), "|" + "---|" * len(t.head)]
        out = [] if t.rows and isinstance(t.rows[0], GroupRow) else list(head)
        for r in t.rows:
            if isinstance(r, GroupRow):
                out += ([""] if out else []) + ["#" * (r.md_level or 4) + " " + self.inline(r.content), ""] + head
            else:
                out.append(self.cells(r.cells))
        return out

    def cards(self, t):
        labels = list(dict.fromkeys(k for c in t.cards for k, _ in c.values))
        head = list(t.key_head) + ["status", t.notes_head] + labels + [t.figures_head]
        rows = []
        for c in t.cards:
            values = dict(c.values)
            notes = "; ".join(s for s in (self.inline(n).strip() for n in _items(c.notes)) if s)
            figures = " ".join(f"[{f.caption}]({f.src})" if isinstance(f, Figure) else self.inline(f).strip()
                               for f in _items(c.figures))
            rows.append(Row(list(c.keys) + [c.status, notes] + [values.get(k, "") for k in labels] + [figures]))
        return self.table(Table(head, rows))

    def document(self, nodes):
        return "\n".join(self.blocks(nodes)) + "\n"


# ---- HTML -----------------------------------------------------------------------------------------

def _attrs(**kw):
    """' class="x" id="y"': the attributes given (None left out), escaped."""
    return "".join(f' {k.rstrip("_").replace("_", "-")}="{esc(v)}"' for k, v in kw.items() if v is not None)


class HtmlRenderer:
    """Blocks to HTML, one block a line; file paths prefixed with base (the page's way up)."""

    def __init__(self, base="../"):
        self.base = base

    def href(self, path):
        return path if path.startswith("#") else self.base + path

    def inline(self, content):
        return "".join(self.one(x) for x in _items(content))

    def one(self, x):
        if isinstance(x, str):
            return esc(x)
        if isinstance(x, Link):
            return f'<a href="{esc(self.href(x.href))}">{self.inline(x.text)}</a>'
        if isinstance(x, Strong):
            return f"<b>{self.inline(x.content)}</b>"
        if isinstance(x, Em):
            return f"<i>{self.inline(x.content)}</i>"
        if isinstance(x, Code):
            return f"<code>{self.inline(x.content)}</code>"
        if isinstance(x, Span):
            tag = "div" if x.block else "span"
            return f"<{tag}{_attrs(class_=x.cls, title=x.title)}>{self.inline(x.content)}</{tag}>"
        if isinstance(x, More):
            return self.more(x)
        if isinstance(x, Media):
            return self.media(x)
        if isinstance(x, Raw):
            return x.html
        raise TypeError(f"not inline: {x!r}")

    def more(self, x):
        keep = x.keep or 180
        if x.summary is not None:
            return (f'<details class="more"><summary>{esc(x.summary)}</summary>'
                    f'<div class="params">{esc(x.text)}</div></details>')
        if len(x.text) <= keep + 40:
            return esc(x.text)
        return f"<details class=\"more\"><summary>{esc(x.text[:keep])}…</summary>{esc(x.text[keep:])}</details>"

    def media(self, x):
        if x.exists:
            extra = "".join(f' {k}="{esc(v)}"' for k, v in (x.attrs or {}).items())
            return f'<img{extra} src="{esc(self.href(x.src))}" alt="{esc(x.caption)}" loading="lazy">'
        where = x.src or "no file named"
        return (f'<div class="placeholder" data-missing="{esc(where)}">{esc(x.caption)}: not written here'
                f'<br><small>{esc(where)}</small></div>')

    def blocks(self, nodes):
        return "\n".join(s for s in (self.block(n) for n in _items(nodes)) if s)

    def block(self, n):
        if isinstance(n, Heading):
            return f"<h{n.level}{_attrs(id=n.id)}>{self.inline(n.content)}</h{n.level}>"
        if isinstance(n, Para):
            return f"<p{_attrs(class_=n.cls)}>{self.inline(n.content)}</p>"
        if isinstance(n, Bullets):
            return "<ul>" + "".join(f"<li>{self.inline(x)}</li>" for x in n.items) + "</ul>"
        if isinstance(n, Table):
            return self.table(n)
        if isinstance(n, Figure):
            return (f'<figure class="{esc(n.cls or "")}"><img src="{esc(self.href(n.src))}" alt="{esc(n.caption)}" '
                    f'loading="lazy"><figcaption>{esc(n.caption)}</figcaption></figure>')
        if isinstance(n, Box):
            tag = n.tag or "div"
            return f"<{tag}{_attrs(class_=n.cls, id=n.id)}>" + self.blocks(n.children) + f"</{tag}>"
        if isinstance(n, Details):
            return (f"<details{_attrs(class_=n.cls, id=n.id)}><summary>{self.inline(n.summary)}</summary>"
                    + self.blocks(n.children) + "</details>")
        if isinstance(n, Cards):
            return "\n".join(self.card(c) for c in n.cards)
        if isinstance(n, Only):
            return self.blocks(n.children) if n.fmt == HTML else ""
        if isinstance(n, Raw):
            return n.html
        raise TypeError(f"not a block: {n!r}")

    def card(self, c):
        title = " · ".join(s for s in (self.inline(k) for k in c.keys) if s)
        return "\n".join(
            [f'<div{_attrs(class_=c.cls)}><h4>{title} <span class="status">{esc(c.status)}</span></h4>'
             + "\n".join(self.inline(n) for n in _items(c.notes))]
            + ["<dl>" + "".join(f"<dt>{esc(k)}</dt><dd>{self.inline(v)}</dd>" for k, v in c.values)
               + '</dl><div class="images">']
            + [self.block(f) if isinstance(f, Figure) else self.inline(f) for f in _items(c.figures)]
            + ["</div></div>"])

    def cell(self, c, rowspan=None):
        c = c if isinstance(c, Cell) else Cell(c)
        tag = "th" if c.header else "td"
        return f"<{tag}{_attrs(class_=c.cls, title=c.title, rowspan=rowspan)}>{self.inline(c.content)}</{tag}>"

    def row(self, r, width, spans):
        if isinstance(r, GroupRow):
            return f'<tr{_attrs(class_=r.cls)}><th colspan="{width}">{self.inline(r.content)}</th></tr>'
        return (f"<tr{_attrs(class_=r.cls, **(r.attrs or {}))}>"
                + "".join(self.cell(c, spans[j] if spans[j] > 1 else None) for j, c in enumerate(r.cells)
                          if spans[j]) + "</tr>")

    def spans(self, t):
        """Per row, each cell's rowspan: 1, more where the cells beneath repeat it (t.merge), 0 for
        a cell merged into the one above."""
        out, above, owner = [], None, {}
        for i, r in enumerate(t.rows):
            if isinstance(r, GroupRow):
                out.append(None)
                above = None
                continue
            mine = [self.cell(c) for c in r.cells]
            out.append([1] * len(mine))
            for j in sorted(t.merge or ()):
                if above is None or mine[j] != above[j]:
                    break
                out[i][j] = 0
                out[owner[j]][j] += 1
            for j in range(len(mine)):
                if out[i][j]:
                    owner[j] = i
            above = mine
        return out

    def table(self, t):
        head = "".join(self.cell(c if isinstance(c, Cell) else Cell(c, header=True)) for c in t.head)
        rows = [self.row(r, len(t.head), s) for r, s in zip(t.rows, self.spans(t))]
        return "\n".join([f"<table{_attrs(id=t.id, class_=t.cls)}><thead><tr>{head}</tr></thead><tbody>"]
                         + rows + ["</tbody></table>"])


def to_markdown(nodes):
    return MarkdownRenderer().document(nodes)


def to_html(nodes, base="../"):
    return HtmlRenderer(base).blocks(nodes)
