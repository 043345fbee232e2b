// pst report viewer: sortable tables and per-scene image viewers (toggle, before/after slider,
// zoom that shows pixels as pixels, value under the cursor). Plain JS, no network; inlined into
// the page by scripts/pstlib/report/html.py. A viewer is a div.pv holding a JSON script element
// {"name": scene, "layers": [{"label", "kind", "src"}], "a": index, "b": index}, its images as
// data: URIs, so the canvas stays readable (getImageData) from file://.
"use strict";

(function () {
  // ---------------------------------------------------------------------------------------
  // Sortable tables: <table class="sortable">, numbers in td[data-v]; click a header to sort,
  // again to reverse. The page's own order (failures first) is the initial one.
  function sortTable(table, col, th) {
    const body = table.tBodies[0];
    const rows = Array.from(body.rows);
    const dir = th.getAttribute("aria-sort") === "ascending" ? -1 : 1;
    const key = (row) => {
      const td = row.cells[col];
      const v = td.getAttribute("data-v");
      if (v !== null && v !== "") return Number(v);
      return td.textContent.trim().toLowerCase();
    };
    rows.sort((x, y) => {
      const a = key(x), b = key(y);
      if (typeof a === "number" && typeof b === "number") return dir * (a - b);
      return dir * String(a).localeCompare(String(b), undefined, { numeric: true });
    });
    for (const h of table.tHead.rows[0].cells) h.removeAttribute("aria-sort");
    th.setAttribute("aria-sort", dir > 0 ? "ascending" : "descending");
    for (const r of rows) body.appendChild(r);
  }

  function initTables() {
    for (const table of document.querySelectorAll("table.sortable")) {
      if (!table.tHead || !table.tBodies.length) continue;
      Array.from(table.tHead.rows[0].cells).forEach((th, i) => {
        th.tabIndex = 0;
        th.title = "sort";
        th.addEventListener("click", () => sortTable(table, i, th));
        th.addEventListener("keydown", (e) => { if (e.key === "Enter") sortTable(table, i, th); });
      });
    }
  }

  // ---------------------------------------------------------------------------------------
  // Viewer
  const FIT = 640;          // canvas side in CSS pixels that an image is fitted to

  function el(tag, attrs, text) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function layerSelect(layers, value, title) {
    const s = el("select", { title: title });
    layers.forEach((l, i) => {
      const o = el("option", { value: String(i) }, l.label);
      if (i === value) o.selected = true;
      s.appendChild(o);
    });
    return s;
  }

  function Viewer(root) {
    const spec = JSON.parse(root.querySelector("script[type='application/json']").textContent);
    const L = spec.layers;
    const st = {
      a: Math.min(spec.a || 0, L.length - 1),
      b: Math.min(spec.b === undefined ? 1 : spec.b, L.length - 1),
      show: "a",            // the layer on screen when not in slider mode: a | b
      slider: false,
      split: 0.5,           // slider position, fraction of the canvas width
      zoom: 1,              // integer magnification on top of the fit
      ox: 0, oy: 0,         // image pixel at the canvas's top left
      loaded: 0,
    };
    const imgs = L.map(() => new Image());
    const pixels = L.map(() => null);   // ImageData per layer for the readout (false: unreadable)

    // Controls
    const bar = el("div", { class: "pv-bar" });
    const selA = layerSelect(L, st.a, "image A");
    const selB = layerSelect(L, st.b, "image B");
    const toggle = el("button", { type: "button", class: "pv-toggle", title: "show A or B (key t)" }, "A");
    const sliderBox = el("input", { type: "checkbox", class: "pv-slider-on", title: "before/after slider" });
    const split = el("input", { type: "range", min: "0", max: "1000", value: "500", class: "pv-split",
                                title: "slider: A left, B right" });
    split.disabled = true;
    const zoomOut = el("button", { type: "button", class: "pv-zoom-out", title: "zoom out (-)" }, "\u2212");
    const zoomLabel = el("span", { class: "pv-zoom" }, "1x");
    const zoomIn = el("button", { type: "button", class: "pv-zoom-in", title: "zoom in (+, wheel)" }, "+");
    const zoomFit = el("button", { type: "button", class: "pv-zoom-fit", title: "whole image (0)" }, "fit");
    const lab = (t, c) => { const s = el("label", {}); s.append(t, c); return s; };
    bar.append(lab("A ", selA), lab(" B ", selB), toggle, lab(" slider ", sliderBox), split,
               el("span", { class: "pv-sep" }), zoomOut, zoomLabel, zoomIn, zoomFit);
    const canvas = el("canvas", { class: "pv-canvas", tabindex: "0" });
    const readout = el("div", { class: "pv-readout" }, "move the cursor over the image for pixel values");
    root.append(bar, canvas, readout);
    const ctx = canvas.getContext("2d");

    let W = 1, H = 1, fit = 1;
    function geometry() {
      const first = imgs.find((i) => i.naturalWidth > 0) || imgs[0];
      W = first.naturalWidth || 1;
      H = first.naturalHeight || 1;
      const side = Math.max(W, H);
      fit = side <= FIT ? Math.floor(FIT / side) : FIT / side;
      canvas.width = Math.round(W * fit);
      canvas.height = Math.round(H * fit);
    }

    function clampView() {
      const vw = W / st.zoom, vh = H / st.zoom;
      st.ox = Math.max(0, Math.min(W - vw, Math.round(st.ox)));
      st.oy = Math.max(0, Math.min(H - vh, Math.round(st.oy)));
    }

    function drawLayer(i, clipX) {
      const img = imgs[i];
      if (!img.naturalWidth) return;
      // A layer of another size (ground truth at the scene's own size) is mapped onto the first's.
      const sx = img.naturalWidth / W, sy = img.naturalHeight / H;
      ctx.save();
      if (clipX !== undefined) {
        ctx.beginPath();
        ctx.rect(clipX, 0, canvas.width - clipX, canvas.height);
        ctx.clip();
      }
      ctx.imageSmoothingEnabled = false;
      ctx.drawImage(img, st.ox * sx, st.oy * sy, (W / st.zoom) * sx, (H / st.zoom) * sy,
                    0, 0, canvas.width, canvas.height);
      ctx.restore();
    }

    function draw() {
      ctx.imageSmoothingEnabled = false;
      ctx.fillStyle = "#000";
      ctx.fillRect(0, 0, canvas.width, canvas.height);
      if (st.slider) {
        const x = Math.round(st.split * canvas.width);
        drawLayer(st.a);
        drawLayer(st.b, x);
        ctx.fillStyle = "#ff0";
        ctx.fillRect(Math.max(0, x - 1), 0, 1, canvas.height);
      } else {
        drawLayer(st.show === "a" ? st.a : st.b);
      }
      toggle.textContent = st.slider ? `${L[st.a].label} | ${L[st.b].label}`
                                     : (st.show === "a" ? "A: " : "B: ") + L[st.show === "a" ? st.a : st.b].label;
      zoomLabel.textContent = st.zoom + "x";
      root.dataset.show = st.slider ? "slider" : st.show;
      root.dataset.zoom = String(st.zoom);
    }

    function setZoom(z, cx, cy) {
      // Keep the image pixel under (cx, cy) (canvas pixels) in place.
      z = Math.max(1, Math.min(64, z));
      const px = st.ox + (cx / canvas.width) * (W / st.zoom);
      const py = st.oy + (cy / canvas.height) * (H / st.zoom);
      st.zoom = z;
      st.ox = px - (cx / canvas.width) * (W / z);
      st.oy = py - (cy / canvas.height) * (H / z);
      clampView();
      draw();
    }

    function pixelAt(e) {
      const r = canvas.getBoundingClientRect();
      const cx = (e.clientX - r.left) * (canvas.width / r.width);
      const cy = (e.clientY - r.top) * (canvas.height / r.height);
      return { cx, cy, x: Math.floor(st.ox + (cx / canvas.width) * (W / st.zoom)),
               y: Math.floor(st.oy + (cy / canvas.height) * (H / st.zoom)) };
    }

    function value(i, x, y) {
      if (pixels[i] === null && imgs[i].naturalWidth) pixels[i] = readPixels(imgs[i]);
      const p = pixels[i];
      if (!p) return null;
      const lx = Math.floor((x * p.width) / W), ly = Math.floor((y * p.height) / H);
      if (lx < 0 || ly < 0 || lx >= p.width || ly >= p.height) return null;
      const o = 4 * (ly * p.width + lx);
      return [p.data[o], p.data[o + 1], p.data[o + 2]];
    }

    function showValues(x, y) {
      if (x < 0 || y < 0 || x >= W || y >= H) return;
      readout.textContent = "";
      readout.appendChild(el("b", {}, `x ${x}, y ${y}`));
      L.forEach((l, i) => {
        const v = value(i, x, y);
        const span = el("span", { class: "pv-val" + (i === st.a ? " pv-a" : "") + (i === st.b ? " pv-b" : "") },
                        `${l.label}: ${v ? v.join(" ") : "n/a"}`);
        if (v) {
          const sw = el("i", { class: "pv-swatch" });
          sw.style.background = `rgb(${v[0]},${v[1]},${v[2]})`;
          span.prepend(sw);
        }
        readout.appendChild(span);
      });
    }

    // Events
    selA.addEventListener("change", () => { st.a = Number(selA.value); st.show = "a"; draw(); });
    selB.addEventListener("change", () => { st.b = Number(selB.value); st.show = "b"; draw(); });
    toggle.addEventListener("click", () => { st.slider = false; sliderBox.checked = false; split.disabled = true;
                                             st.show = st.show === "a" ? "b" : "a"; draw(); });
    sliderBox.addEventListener("change", () => { st.slider = sliderBox.checked; split.disabled = !st.slider; draw(); });
    split.addEventListener("input", () => { st.split = Number(split.value) / 1000; draw(); });
    zoomIn.addEventListener("click", () => setZoom(st.zoom * 2, canvas.width / 2, canvas.height / 2));
    zoomOut.addEventListener("click", () => setZoom(Math.floor(st.zoom / 2), canvas.width / 2, canvas.height / 2));
    zoomFit.addEventListener("click", () => { st.zoom = 1; st.ox = st.oy = 0; draw(); });
    canvas.addEventListener("wheel", (e) => {
      e.preventDefault();
      const p = pixelAt(e);
      setZoom(e.deltaY < 0 ? st.zoom * 2 : Math.floor(st.zoom / 2), p.cx, p.cy);
    }, { passive: false });
    let drag = null;
    canvas.addEventListener("mousedown", (e) => { drag = { x: e.clientX, y: e.clientY, ox: st.ox, oy: st.oy }; });
    window.addEventListener("mouseup", () => { drag = null; });
    canvas.addEventListener("mousemove", (e) => {
      const p = pixelAt(e);
      if (drag && st.zoom > 1) {
        const r = canvas.getBoundingClientRect();
        st.ox = drag.ox - ((e.clientX - drag.x) / r.width) * (W / st.zoom);
        st.oy = drag.oy - ((e.clientY - drag.y) / r.height) * (H / st.zoom);
        clampView();
        draw();
      }
      showValues(p.x, p.y);
    });
    canvas.addEventListener("keydown", (e) => {
      if (e.key === "t") toggle.click();
      else if (e.key === "+" || e.key === "=") zoomIn.click();
      else if (e.key === "-") zoomOut.click();
      else if (e.key === "0") zoomFit.click();
      else return;
      e.preventDefault();
    });

    // Images: data: URIs, decoded once; each one's pixels read at the first readout.
    function readPixels(img) {
      const c = document.createElement("canvas");
      c.width = img.naturalWidth;
      c.height = img.naturalHeight;
      const x = c.getContext("2d", { willReadFrequently: true });
      x.drawImage(img, 0, 0);
      try { return x.getImageData(0, 0, c.width, c.height); } catch (err) { return false; }
    }
    L.forEach((l, i) => {
      imgs[i].onload = () => {
        st.loaded += 1;
        root.dataset.loaded = String(st.loaded);
        geometry();
        clampView();
        draw();
      };
      imgs[i].onerror = () => { console.error("pst viewer: cannot load " + l.label); };
      imgs[i].alt = l.label;
      imgs[i].src = l.src;
    });
    root.pvState = st;
    root.pvImages = imgs;
  }

  function init() {
    initTables();
    for (const v of document.querySelectorAll(".pv")) Viewer(v);
  }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", init);
  else init();
})();
