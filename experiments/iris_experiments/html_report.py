"""Self-contained HTML report of an experiment: provenance, settings, conclusions, tables, plots
and interactive image comparisons (swipe, flip, false-colour error map, zoom, exposure, pixel
read-out). Everything is inlined (figures as data: URIs, images as base64 float16, the viewer's
JavaScript and CSS), so the page needs no network and no other file. Tested in headless Chromium
by experiments/tests/browser_check.py."""
from __future__ import annotations

import base64
import html
import json
import re
from pathlib import Path

import numpy as np

from . import exr

MAX_SIDE = 256        # images are subsampled (every k-th pixel) to at most this many pixels per side
MAX_TESTS = 8         # test images per comparison
# The viewers' pixels of one report, in bytes of base64 text (each pixel 3 float16 = 6 bytes, 8 as
# base64): a report with many comparisons takes a larger step for all of them, so that its viewers
# stay within 2 MB (per_bounce_phase's ten 256² images made a 5.8 MiB page at MAX_SIDE alone).
PAYLOAD_BUDGET = 2_000_000


def _inline(text: str) -> str:
    """Markdown inline subset used by the experiments: `code`, **bold**, [text](link)."""
    out = html.escape(text, quote=False)
    out = re.sub(r"`([^`]+)`", r"<code>\1</code>", out)
    out = re.sub(r"\*\*([^*]+)\*\*", r"<b>\1</b>", out)
    return re.sub(r"\[([^\]]+)\]\(([^)\s]+)\)", lambda m: f'<a href="{html.escape(m.group(2))}">{m.group(1)}</a>', out)


def _table(lines) -> str:
    def cells(line):
        parts = re.split(r"(?<!\\)\|", line.strip())[1:-1]
        return [p.strip().replace("\\|", "|") for p in parts]
    head, body = cells(lines[0]), [cells(l) for l in lines[2:]]
    th = "".join(f"<th>{_inline(c)}</th>" for c in head)
    rows = "".join("<tr>" + "".join(f"<td>{_inline(c)}</td>" for c in r) + "</tr>" for r in body)
    return f"<table><thead><tr>{th}</tr></thead><tbody>{rows}</tbody></table>"


def markdown_to_html(text: str) -> str:
    """Blocks separated by blank lines: tables (lines starting with '|'), indented code, paragraphs."""
    out = []
    for block in re.split(r"\n\s*\n", text.strip()):
        lines = block.splitlines()
        if lines and all(l.lstrip().startswith("|") for l in lines) and len(lines) >= 2:
            out.append(_table(lines))
        elif lines and all(l.startswith("    ") for l in lines):
            out.append("<pre>" + html.escape("\n".join(l[4:] for l in lines)) + "</pre>")
        elif block.strip():
            out.append("<p>" + _inline(" ".join(l.strip() for l in lines)) + "</p>")
    return "\n".join(out)


def data_uri(path: Path) -> str:
    path = Path(path)
    mime = {".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg"}[path.suffix.lower()]
    return f"data:{mime};base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def image_payload(path: Path, step: int) -> dict:
    """An EXR's colour channels as base64 little-endian float16, every `step`-th pixel."""
    pixels, names, _ = exr.read_exr(str(path))
    rgb = exr.rgb_of(pixels, names)[::step, ::step, :3]
    rgb = np.nan_to_num(rgb.astype(np.float32), nan=0.0, posinf=65504.0, neginf=0.0)
    data = np.clip(rgb, -65504, 65504).astype("<f2")
    return {"width": int(rgb.shape[1]), "height": int(rgb.shape[0]),
            "data": base64.b64encode(data.tobytes()).decode("ascii")}


def _shown(comp: dict) -> tuple[int, int, list]:
    """Full width and height of a comparison's reference (from its header), and the test images
    that are shown."""
    w, h = exr.exr_size(str(comp["reference"]))
    return w, h, [(label, p) for label, p in comp["tests"] if Path(p).exists()][:MAX_TESTS]


def _ceil_div(a: int, b: int) -> int:
    return -(-a // b)


def payload_bytes(w: int, h: int, images: int, step: int) -> int:
    """Base64 bytes of `images` images of w×h shown at every `step`-th pixel (3 float16 each)."""
    return images * 4 * _ceil_div(_ceil_div(w, step) * _ceil_div(h, step) * 6, 3)


def report_min_step(comparisons, budget: int = PAYLOAD_BUDGET, shown=None) -> int:
    """The smallest step, at least each comparison's MAX_SIDE step, that keeps all viewers' pixels
    of a report within `budget` bytes (stepping further only when one step cannot). `shown`: the
    comparisons' _shown, when the caller has them already."""
    shown = shown if shown is not None else [_shown(c) for c in comparisons]
    step = 1
    while step < 64 and sum(payload_bytes(w, h, 1 + len(t), max(step, _ceil_div(max(w, h), MAX_SIDE)))
                            for w, h, t in shown) > budget:
        step += 1
    return step


def comparison_payload(comp: dict, min_step: int = 1, shown=None) -> dict:
    """{"title", "reference": EXR, "tests": [(label, EXR)]} → the viewer's data (one subsampling
    step for all images of the comparison, so that pixels line up; at least `min_step`, the
    report's step from report_min_step; `shown`: the comparison's _shown, when known)."""
    w, h, tests = shown if shown is not None else _shown(comp)
    step = max(min_step, _ceil_div(max(w, h), MAX_SIDE))
    return {"title": comp["title"], "step": step, "full_size": [w, h],
            "reference": {"label": "reference", **image_payload(comp["reference"], step)},
            "tests": [{"label": label, **image_payload(p, step)} for label, p in tests]}


_CSS = """
body{font-family:system-ui,sans-serif;margin:1.5em auto;max-width:1100px;padding:0 1em;color:#222}
h1{font-size:1.5em} h2{font-size:1.2em;border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0;display:block;overflow-x:auto}
th,td{border:1px solid #ccc;padding:.2em .5em;text-align:right} th{background:#f0f0f0}
td:first-child,th:first-child{text-align:left} code,pre{background:#f5f5f5;font-size:.9em}
pre{padding:.5em;overflow-x:auto} .figure{max-width:100%;border:1px solid #ddd;margin:.4em 0}
.provenance.dirty{background:#fee;border:1px solid #c00;padding:.4em}
.provenance.clean{background:#efe;border:1px solid #393;padding:.4em}
.viewer{border:1px solid #bbb;padding:.6em;margin:1em 0} .controls{display:flex;flex-wrap:wrap;gap:.6em;align-items:center;font-size:.9em}
.stage{overflow:auto;max-height:70vh;margin-top:.5em;background:#444;position:relative}
.stage canvas{image-rendering:pixelated;display:block;cursor:crosshair}
.readout{font-family:monospace;font-size:.85em;min-height:2.6em;white-space:pre}
.colorbar{height:10px;width:200px;display:inline-block;vertical-align:middle}
"""

# The viewer: decodes float16 images, draws the reference / test / error map into a canvas.
_JS = r"""
(function(){
'use strict';
function halfToFloat(h){var s=(h&0x8000)?-1:1,e=(h>>10)&0x1f,f=h&0x3ff;
  if(e===0)return s*Math.pow(2,-14)*(f/1024); if(e===31)return f?NaN:s*Infinity;
  return s*Math.pow(2,e-15)*(1+f/1024);}
function decode(img){var bin=atob(img.data),n=bin.length/2,out=new Float32Array(n);
  for(var i=0;i<n;i++){out[i]=halfToFloat(bin.charCodeAt(2*i)|(bin.charCodeAt(2*i+1)<<8));}
  return out;}
function srgb(x){x=x<0?0:(x>1?1:x);return x<=0.0031308?12.92*x:1.055*Math.pow(x,1/2.4)-0.055;}
// Perceptually ordered false colours (a coarse viridis-like ramp, interpolated).
var RAMP=[[68,1,84],[72,40,120],[62,74,137],[49,104,142],[38,130,142],[31,158,137],[53,183,121],[109,205,89],[180,222,44],[253,231,37]];
function ramp(t){t=t<0?0:(t>1?1:t);var x=t*(RAMP.length-1),i=Math.min(RAMP.length-2,Math.floor(x)),f=x-i;
  return [0,1,2].map(function(k){return Math.round(RAMP[i][k]+(RAMP[i+1][k]-RAMP[i][k])*f);});}
var ERR_LO=-4,ERR_HI=1; // log10 of the per-pixel relative squared error shown from blue to yellow
function relErr(t,r,i){var s=0;for(var k=0;k<3;k++){var d=t[3*i+k]-r[3*i+k];s+=d*d/(r[3*i+k]*r[3*i+k]+0.01);}return s/3;}
function Viewer(root,data){
  var self=this;this.root=root;this.data=data;this.ref=decode(data.reference);
  this.tests=data.tests.map(function(t){return decode(t);});
  this.w=data.reference.width;this.h=data.reference.height;this.sel=0;this.mode='swipe';this.split=0.5;
  this.showTest=true;this.zoom=Math.max(1,Math.floor(512/Math.max(this.w,this.h)));this.exposure=0;
  var q=function(s){return root.querySelector(s);};
  this.canvas=q('canvas.image');this.canvas.width=this.w;this.canvas.height=this.h;this.ctx=this.canvas.getContext('2d');
  this.readout=q('.readout');
  var sel=q('select.test');data.tests.forEach(function(t,i){var o=document.createElement('option');o.value=i;o.textContent=t.label;sel.appendChild(o);});
  sel.addEventListener('change',function(){self.sel=+sel.value;self.draw();});
  root.querySelectorAll('input[type=radio]').forEach(function(r){r.addEventListener('change',function(){if(r.checked){self.mode=r.value;self.draw();}});});
  var sw=q('input.swipe');sw.addEventListener('input',function(){self.split=sw.value/1000;self.draw();});
  q('button.flip').addEventListener('click',function(){self.showTest=!self.showTest;if(self.mode!=='flip'){self.mode='flip';q('input[value=flip]').checked=true;}self.draw();});
  q('button.zin').addEventListener('click',function(){self.zoom=Math.min(32,self.zoom*2);self.resize();});
  q('button.zout').addEventListener('click',function(){self.zoom=Math.max(1,self.zoom/2);self.resize();});
  var ex=q('input.exposure');ex.addEventListener('input',function(){self.exposure=+ex.value;q('.exposure-value').textContent=(+ex.value).toFixed(1);self.draw();});
  var dragging=false;
  this.canvas.addEventListener('mousedown',function(e){dragging=true;self.drag(e);});
  window.addEventListener('mouseup',function(){dragging=false;});
  this.canvas.addEventListener('mousemove',function(e){if(dragging)self.drag(e);self.read(e);});
  this.canvas.addEventListener('wheel',function(e){e.preventDefault();self.zoom=e.deltaY<0?Math.min(32,self.zoom*2):Math.max(1,self.zoom/2);self.resize();},{passive:false});
  root.addEventListener('keydown',function(e){if(e.key==='f'){q('button.flip').click();}});
  this.resize();
}
Viewer.prototype.pixelAt=function(e){var r=this.canvas.getBoundingClientRect();
  return [Math.floor((e.clientX-r.left)/r.width*this.w),Math.floor((e.clientY-r.top)/r.height*this.h)];};
Viewer.prototype.drag=function(e){if(this.mode!=='swipe')return;var p=this.pixelAt(e);this.split=Math.max(0,Math.min(1,(p[0]+0.5)/this.w));
  this.root.querySelector('input.swipe').value=Math.round(this.split*1000);this.draw();};
Viewer.prototype.read=function(e){var p=this.pixelAt(e),x=p[0],y=p[1];if(x<0||y<0||x>=this.w||y>=this.h)return;
  var i=y*this.w+x,t=this.tests[this.sel],r=this.ref,f=function(a){return [a[3*i],a[3*i+1],a[3*i+2]].map(function(v){return v.toPrecision(4);}).join(', ');};
  this.readout.textContent='pixel ('+x*this.data.step+', '+y*this.data.step+')  reference: '+f(r)+'\n'+
    this.data.tests[this.sel].label+': '+f(t)+'   relative squared error: '+relErr(t,r,i).toPrecision(3);};
Viewer.prototype.resize=function(){this.canvas.style.width=(this.w*this.zoom)+'px';this.canvas.style.height=(this.h*this.zoom)+'px';
  this.root.querySelector('.zoom-value').textContent=this.zoom+'x';this.draw();};
Viewer.prototype.draw=function(){
  var img=this.ctx.createImageData(this.w,this.h),d=img.data,t=this.tests[this.sel],r=this.ref,g=Math.pow(2,this.exposure);
  var cut=Math.round(this.split*this.w);
  for(var y=0;y<this.h;y++)for(var x=0;x<this.w;x++){var i=y*this.w+x,o=4*i,c;
    if(this.mode==='error'){var e=relErr(t,r,i),l=e>0?(Math.log10(e)-ERR_LO)/(ERR_HI-ERR_LO):0;c=ramp(l);}
    else{var src=this.mode==='swipe'?(x<cut?t:r):(this.showTest?t:r);
      c=[0,1,2].map(function(k){return Math.round(255*srgb(src[3*i+k]*g));});
      if(this.mode==='swipe'&&x===cut&&cut>0&&cut<this.w)c=[255,255,255];}
    d[o]=c[0];d[o+1]=c[1];d[o+2]=c[2];d[o+3]=255;}
  this.ctx.putImageData(img,0,0);
  var label=this.mode==='error'?'error map: log10 relative squared error, '+ERR_LO+' .. '+ERR_HI:
    (this.mode==='swipe'?'left: '+this.data.tests[this.sel].label+' | right: reference':(this.showTest?this.data.tests[this.sel].label:'reference'));
  this.root.querySelector('.shown').textContent=label;this.root.dataset.shown=this.mode+':'+(this.showTest?'test':'reference');};
window.irisViewers=[];
document.querySelectorAll('.viewer').forEach(function(root){
  var data=JSON.parse(document.getElementById(root.dataset.payload).textContent);
  window.irisViewers.push(new Viewer(root,data));});
var cb=document.querySelectorAll('canvas.colorbar');cb.forEach(function(c){var x=c.getContext('2d'),im=x.createImageData(c.width,1);
  for(var i=0;i<c.width;i++){var v=ramp(i/(c.width-1));im.data.set([v[0],v[1],v[2],255],4*i);}
  for(var y=0;y<c.height;y++)x.putImageData(im,0,y);});
})();
"""


def _viewer(index: int, payload: dict) -> str:
    pid = f"iris-comparison-{index}"
    note = (f" Shown at 1/{payload['step']} resolution (every {payload['step']}-th pixel of "
            f"{payload['full_size'][0]}×{payload['full_size'][1]}, not averaged, so noise is as in the full image)."
            if payload["step"] > 1 else "")
    data = json.dumps(payload).replace("</", "<\\/")
    return f"""
<div class="viewer" tabindex="0" data-payload="{pid}">
  <h3>{html.escape(payload['title'])}</h3>
  <div class="controls">
    <label>test image <select class="test"></select></label>
    <label><input type="radio" name="mode-{index}" value="swipe" checked> swipe</label>
    <label><input type="radio" name="mode-{index}" value="flip"> flip</label>
    <label><input type="radio" name="mode-{index}" value="error"> error map</label>
    <input class="swipe" type="range" min="0" max="1000" value="500" aria-label="swipe position">
    <button class="flip" type="button" title="toggle test / reference (key f)">flip</button>
    <button class="zout" type="button">−</button><span class="zoom-value"></span><button class="zin" type="button">+</button>
    <label>exposure <input class="exposure" type="range" min="-6" max="6" step="0.5" value="0"> <span class="exposure-value">0.0</span> stops</label>
    <span>error colours: <canvas class="colorbar" width="200" height="10"></canvas> 1e-4 .. 10</span>
  </div>
  <div class="shown"></div>
  <div class="stage"><canvas class="image"></canvas></div>
  <div class="readout">move the mouse over the image for pixel values (linear Rec.709, float16)</div>
  <p>Display: linear values × 2^exposure, clamped, sRGB-encoded. Drag on the image to move the swipe.{note}</p>
  <script type="application/json" id="{pid}">{data}</script>
</div>"""


def write_html_report(path: Path, *, title: str, question: str, provenance: dict, machine: dict, settings: dict,
                      conclusions, sections, figures=(), comparisons=(), command: str = "") -> Path:
    """provenance: report.provenance() (clean commit or not); figures: PNG/JPEG paths; comparisons:
    dicts for comparison_payload. Writes one file with everything inlined."""
    path = Path(path)
    esc = html.escape
    prov_class = "clean" if provenance.get("state") == "clean" else "dirty"
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{esc(title)}</title>",
             f"<style>{_CSS}</style></head><body>", f"<h1>{esc(title)}</h1>", f"<p>{_inline(question)}</p>",
             f"<p class='provenance {prov_class}'>{esc(provenance.get('text', ''))}</p>"]
    if command:
        parts.append(f"<p>Command:</p><pre>{esc(command)}</pre>")
    parts.append("<h2>Conclusions (computed from the data below)</h2><ul>" +
                 "".join(f"<li>{_inline(c)}</li>" for c in conclusions) + "</ul>" if conclusions else
                 "<h2>Conclusions</h2><p>(no conclusions: no results)</p>")
    for fig in figures:
        parts.append(f"<img class='figure' alt='{esc(Path(fig).stem)}' src='{data_uri(fig)}'>")
    shown = [_shown(c) for c in comparisons]  # each reference's size read once, from its header
    min_step = report_min_step(comparisons, shown=shown)
    for i, comp in enumerate(comparisons):
        parts.append(_viewer(i, comparison_payload(comp, min_step, shown[i])))
    for heading, text in sections:
        parts.append(f"<h2>{esc(heading)}</h2>{markdown_to_html(text)}")
    parts.append("<h2>Settings</h2><table><tbody>" + "".join(
        f"<tr><td>{esc(str(k))}</td><td>{esc(str(v))}</td></tr>" for k, v in settings.items()) + "</tbody></table>")
    parts.append("<h2>Machine</h2><table><tbody>" + "".join(
        f"<tr><td>{esc(str(k))}</td><td>{esc(str(v))}</td></tr>" for k, v in machine.items()) + "</tbody></table>")
    parts.append(f"<script>{_JS}</script></body></html>")
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text("\n".join(parts))
    tmp.replace(path)
    return path
