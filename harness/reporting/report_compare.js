/* The gallery's image comparison (report.py's gallery sections): per group, any two of its images
 * (the reference, each technique, their error maps) on one stage, A over B, cut by a split the
 * reader moves; zoom with nearest-pixel view, an exposure in stops (a CSS brightness on the
 * tone-mapped PNGs: a reading aid, not a re-exposure of the linear image), the picked images'
 * numbers from the CSVs beneath. Keys on the focused stage: Left/Right move the split, f swaps A
 * and B, 1-9 pick A (with Shift: B), + and - zoom, e and E change the exposure, 0 resets. */
function Compare(root) {
  var q = function (c) { return root.querySelector(c); };
  var s = {split: 50, zoom: 1, ev: 0};
  var pickA = q('.cmp-pick-a'), pickB = q('.cmp-pick-b'), a = q('.cmp-a'), b = q('.cmp-b');
  var stage = q('.cmp-stage'), view = q('.cmp-view'), split = q('.cmp-split');
  function label(sel) { var o = sel.options[sel.selectedIndex]; return o ? o.text + ': ' + o.dataset.nums : ''; }
  function render() {
    a.src = pickA.value; b.src = pickB.value;
    a.style.clipPath = 'inset(0 ' + (100 - s.split) + '% 0 0)';
    q('.cmp-line').style.left = s.split + '%';
    stage.style.transform = 'scale(' + s.zoom + ')';
    var f = 'brightness(' + Math.pow(2, s.ev) + ')';
    a.style.filter = f; b.style.filter = f;
    split.value = s.split;
    q('.cmp-state').textContent = 'zoom ' + s.zoom + 'x, exposure ' + (s.ev >= 0 ? '+' : '') + s.ev + ' EV';
    q('.cmp-nums').textContent = 'A (left) ' + label(pickA) + ' | B (right) ' + label(pickB);
  }
  function pick(sel, i) { if (i < sel.options.length) sel.selectedIndex = i; }
  this.key = function (e) {
    var k = e.key, done = true;
    if (k === 'ArrowLeft') s.split = Math.max(0, s.split - 5);
    else if (k === 'ArrowRight') s.split = Math.min(100, s.split + 5);
    else if (k === 'f') { var i = pickA.selectedIndex; pickA.selectedIndex = pickB.selectedIndex; pickB.selectedIndex = i; }
    else if (/^[1-9]$/.test(k)) pick(pickA, +k - 1);
    else if (/^Digit[1-9]$/.test(e.code) && e.shiftKey) pick(pickB, +e.code.slice(5) - 1);
    else if (k === '+' || k === '=') s.zoom = Math.min(16, s.zoom * 2);
    else if (k === '-') s.zoom = Math.max(1, s.zoom / 2);
    else if (k === 'e') s.ev = Math.min(6, s.ev + 1);
    else if (k === 'E') s.ev = Math.max(-6, s.ev - 1);
    else if (k === '0') s = {split: 50, zoom: 1, ev: 0};
    else done = false;
    if (done) { e.preventDefault(); render(); }
  };
  view.addEventListener('keydown', this.key);
  split.addEventListener('input', function () { s.split = +split.value; render(); });
  pickA.addEventListener('change', render);
  pickB.addEventListener('change', render);
  this.state = function () { return s; };
  this.parts = {a: a, b: b, pickA: pickA, pickB: pickB};
  render();
}
var compares = Array.prototype.map.call(document.querySelectorAll('.compare'), function (r) { return new Compare(r); });
/* ?check: the first comparison driven by keys as a reader would, its state written into
 * <pre id="compare-check"> once its two images have decoded (tests/report). */
if (location.search.indexOf('check') >= 0 && compares.length) {
  window.addEventListener('load', async function () {
    var c = compares[0], p = c.parts, out = [];
    var press = function (key, code, shift) { c.key(new KeyboardEvent('keydown', {key: key, code: code, shiftKey: !!shift})); };
    out.push('compares ' + compares.length + ' options ' + p.pickA.options.length);
    press('ArrowLeft', 'ArrowLeft');
    out.push('split ' + c.state().split + ' clip ' + p.a.style.clipPath);
    press('2', 'Digit2'); press('!', 'Digit1', true);
    out.push('A ' + p.pickA.selectedIndex + ' B ' + p.pickB.selectedIndex);
    press('+', 'Equal'); press('e', 'KeyE');
    out.push('zoom ' + c.state().zoom + ' ev ' + c.state().ev + ' filter ' + p.a.style.filter);
    var ok = await Promise.all([p.a.decode(), p.b.decode()]).then(function () { return 1; }, function () { return 0; });
    out.push('decoded ' + ok + ' widths ' + p.a.naturalWidth + ' ' + p.b.naturalWidth);
    out.push('nums ' + p.pickA.options[p.pickA.selectedIndex].dataset.nums);
    document.getElementById('compare-check').textContent = out.join('\n');
  });
}
