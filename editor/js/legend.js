// Colour legends over the view: deviation (fraction of T, with T's value) and curvature (the
// mean curvature scale the colours saturate at).
import { $, g4 } from "./store.js";
import { curvatureColour, deviationColour } from "./colours.js";

const css = (f, x) => { const c = [0, 0, 0]; f(x, c, 0); return `rgb(${c.map((v) => Math.round(255 * v)).join(",")})`; };
let shown = "";
export function showLegend(mode, st, curvatureScale) {
  const el = $("legend");
  if (!el) return;
  let key = mode, html = "";
  if (mode === "deviation") {
    const t = Math.max(...st.deviation.tolerance);
    key += t;
    const stops = [0, 0.25, 0.5, 0.75, 1].map((x) => `${css(deviationColour, x)} ${100 * x}%`).join(",");
    html = `<div class="lt">deviation |S − D| / T (T = ${g4(t)})</div>` +
      `<div class="bar" style="background:linear-gradient(to right,${stops})"></div>` +
      `<div class="ticks"><span>0</span><span>T/2</span><span>T</span></div>` +
      `<div class="over"><span class="sw" style="background:${css(deviationColour, 2)}"></span> over T</div>`;
  } else if (mode === "curvature") {
    key += curvatureScale;
    const stops = [-1, -0.5, 0, 0.5, 1].map((x) => `${css(curvatureColour, x)} ${50 * (x + 1)}%`).join(",");
    html = `<div class="lt">mean curvature H</div>` +
      `<div class="bar" style="background:linear-gradient(to right,${stops})"></div>` +
      `<div class="ticks"><span>−${g4(curvatureScale)}</span><span>0</span><span>+${g4(curvatureScale)}</span></div>`;
  } else if (mode === "zebra") {
    html = `<div class="lt">zebra: reflection lines (breaks show kinks, bends show curvature jumps)</div>`;
  }
  if (key === shown) return;
  shown = key;
  el.innerHTML = html;
  el.style.display = html ? "block" : "none";
  el.dataset.mode = mode;
}
