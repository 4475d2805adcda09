#!/usr/bin/env python3
"""The report's document model (harness/reporting/report_model.py): one tiny document rendered to
Markdown and to HTML carries the same headings, table cells and figure sources in both, so the two
formats cannot drift; what only the page shows (Only, Raw) stays out of the Markdown; merged cells
(Table.merge) are one cell across rows on the page and repeated in every Markdown row; Cards are
blocks on the page and a table row each in Markdown, with the same values."""
import re
import sys

from reporting import report_model as M

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


doc = [M.Heading(1, "tiny report"),
       M.Box([M.Heading(2, "Answer", id="answer"), M.Para(["least error: ", M.Strong("lrsm"), " 12 ms"])],
             cls="first-screen"),
       M.Table(["claim", "verdict"], [M.GroupRow("Paper A", cls="paper"),
                                      M.Row(["memory | bytes", M.Cell("reproduced", cls="verdict")]),
                                      M.Row(["error", M.Cell(M.More("x" * 300))])], id="claims"),
       M.Figure("plots/tiny_time.png", "tiny_time"),
       M.Table(["reference", "lrsm"], [M.Row([M.Media("gallery/ref.webp", "reference", True),
                                              M.Media("gallery/absent.webp", "lrsm", False)])]),
       M.Details("tiny matrix", [M.Para("rows")], cls="matrix", md_title="tiny matrix"),
       M.Only(M.HTML, M.Raw("<nav>page only</nav>", [])),
       M.Bullets(["one", "two"])]
md = M.to_markdown(doc)
page = M.to_html(doc)
print(md)

md_heads = re.findall(r"^#+ (.*)$", md, re.M)
html_heads = [re.sub(r"<[^>]+>", "", h) for h in re.findall(r"<h\d[^>]*>(.*?)</h\d>", page)]
check(md_heads == ["tiny report", "Answer", "Paper A", "tiny matrix"], f"Markdown headings ({md_heads})")
check(html_heads == ["tiny report", "Answer"], f"HTML headings ({html_heads})")
check("Paper A" in page and "tiny matrix" in page, "the group row and the details' summary on the page")
for cell in ("memory | bytes", "reproduced", "error", "x" * 180):
    check(cell.replace("|", "\\|") in md and cell in page, f"the cell {cell[:20]!r} in both")
check("x" * 300 in md and '<details class="more">' in page, "a long text whole in Markdown, collapsed on the page")
check("![tiny_time](plots/tiny_time.png)" in md and 'src="../plots/tiny_time.png"' in page,
      "the figure's source in both (the page one folder down)")
check("![reference](gallery/ref.webp)" in md and 'src="../gallery/ref.webp"' in page, "an image in both")
check("*lrsm: not written here*" in md and 'data-missing="gallery/absent.webp"' in page,
      "an absent image a placeholder in both")
check("page only" not in md and "<nav>page only</nav>" in page, "what only the page shows stays out of Markdown")
check("- one" in md and "<li>two</li>" in page, "the list in both")
check("**lrsm**" in md and "<b>lrsm</b>" in page, "inline emphasis in both")

links = [M.Details("every group", [M.Para(["see ", M.Link("images", "#g-ao", md_href="#gallery")])], md_level=0)]
check(M.to_markdown(links) == "see [images](#gallery)\n" and '<a href="#g-ao">images</a>' in M.to_html(links),
      "a link to an anchor only the page has: its Markdown target; a Details at md_level 0: no Markdown heading")

# Merged cells: the page's rowspan and Markdown's repeated cells carry the same table.
merged = M.Table(["component", "scene", "front"],
                 [M.Row([M.Cell("ao", header=True), "sponza", "a"]), M.Row([M.Cell("ao", header=True), "sponza", "b"]),
                  M.Row([M.Cell("ao", header=True), "ring", "c"]), M.Row([M.Cell("direct", header=True), "ring", "d"]),
                  M.GroupRow("next"), M.Row([M.Cell("direct", header=True), "ring", "e"])], merge=[0, 1])
md_rows = [[c.strip() for c in line.split("|")[1:-1]] for line in M.to_markdown(merged).splitlines()
           if line.startswith("| ") and "component" not in line]
page_rows = re.findall(r"<tr>(.*?)</tr>", M.to_html(merged))[1:]
want = [["ao", "sponza", "a"], ["ao", "sponza", "b"], ["ao", "ring", "c"], ["direct", "ring", "d"], ["direct", "ring", "e"]]
check(md_rows == want, f"Markdown repeats merged cells in every row ({md_rows})")
spans = [re.findall(r'<t[hd](?: rowspan="(\d+)")?>([^<]*)</t[hd]>', r) for r in page_rows if "colspan" not in r]
check(spans == [[("3", "ao"), ("2", "sponza"), ("", "a")], [("", "b")], [("", "ring"), ("", "c")],
                [("", "direct"), ("", "ring"), ("", "d")], [("", "direct"), ("", "ring"), ("", "e")]],
      f"the page merges a repeated cell (and a column only within its merged parent; not across a group row) ({spans})")
unfolded, pending = [], [("", 0)] * 3  # the page's rows, each rowspan cell put back in the rows it spans
for r in spans:
    cells, row = iter(r), []
    for j in range(3):
        if pending[j][1] == 0:
            span, text = next(cells)
            pending[j] = (text, int(span or 1))
        row.append(pending[j][0])
        pending[j] = (pending[j][0], pending[j][1] - 1)
    unfolded.append(row)
check(unfolded == want, f"both formats carry the same cells ({unfolded})")

# Cards: the page's blocks and Markdown's table rows carry the same keys, values and figures.
cards = M.Cards([M.Card(["cornell", "lrsm", "64x64", ""], "ok", [M.Span("a=1", cls="params", block=True)],
                        [("GPU ms", "1.5"), ("RMSE", "0.1 (ref noise 0)")],
                        [M.Figure("images/m/ref.png", "reference"), M.Figure("images/m/x.png", "technique")],
                        cls="row status-ok"),
                 M.Card(["ring", "vct", "64x64", "t=1"], "stale",
                        [M.Span("b=2", cls="params", block=True), M.Span("changed", cls="message", block=True)],
                        [("GPU ms", "2"), ("FLIP", "0.3")], [M.Span("no images", cls="noimg", block=True)],
                        cls="row status-stale")], ("scene", "technique", "size", "instant"), "settings", "images")
md = M.to_markdown(cards).splitlines()
page = M.to_html(cards)
check(md[0] == "| scene | technique | size | instant | status | settings | GPU ms | RMSE | FLIP | images |",
      f"Markdown's columns: keys, status, notes, every value label in order, figures ({md[0]})")
check(md[2] == "| cornell | lrsm | 64x64 |  | ok | a=1 | 1.5 | 0.1 (ref noise 0) |  | "
      "[reference](images/m/ref.png) [technique](images/m/x.png) |", f"a card's Markdown row ({md[2]})")
check(md[3] == "| ring | vct | 64x64 | t=1 | stale | b=2; changed | 2 |  | 0.3 | no images |",
      f"a card lacking a value: an empty cell ({md[3]})")
blocks = re.findall(r'<div class="row[^"]*">(.*?)</div></div>', page, re.S)
check(len(blocks) == 2 and "<h4>cornell · lrsm · 64x64 <span class=\"status\">ok</span></h4>" in blocks[0]
      and "<h4>ring · vct · 64x64 · t=1" in blocks[1], "a card's block: its keys and status as a heading")
check("<dt>RMSE</dt><dd>0.1 (ref noise 0)</dd>" in blocks[0] and "<dt>FLIP</dt>" not in blocks[0]
      and "<dt>FLIP</dt><dd>0.3</dd>" in blocks[1], "a card's block: its own values only")
check(re.findall(r"<figcaption>([^<]*)</figcaption>", blocks[0]) == ["reference", "technique"]
      and 'src="../images/m/x.png"' in blocks[0] and '<div class="message">changed</div>' in blocks[1]
      and '<div class="noimg">no images</div>' in blocks[1], "a card's block: its notes and figures")
print("FAIL" if failures else "PASS", f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
