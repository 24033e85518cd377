// romdyn's mode-shape viewer: the model's nodes and the lines between connected nodes,
// orthographic 3-D on a canvas, each kept mode animated as x0 + a Re(v e^{i phi}); drag to
// turn, the list to choose a mode. No library and no network: the data are in the page.
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("romdyn-geometry").textContent);
  const canvas = document.getElementById("viewer");
  const ctx = canvas.getContext("2d");
  const select = document.getElementById("mode");
  const play = document.getElementById("play");
  data.modes.forEach((m, k) => {
    const o = document.createElement("option");
    o.value = k;
    o.textContent = m.label;
    select.appendChild(o);
  });
  // Model size: the bounding box's diagonal; the largest displacement is drawn at 10 % of it.
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  data.nodes.forEach((p) => p.forEach((x, i) => { lo[i] = Math.min(lo[i], x); hi[i] = Math.max(hi[i], x); }));
  const centre = lo.map((l, i) => (l + hi[i]) / 2);
  const size = Math.max(1e-12, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
  let yaw = 0.6, pitch = 0.4, running = true, t0 = performance.now(), phase = 0;
  function project(p) {
    const x = p[0] - centre[0], y = p[1] - centre[1], z = p[2] - centre[2];
    const cy = Math.cos(yaw), sy = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
    const x1 = cy * x + sy * z, z1 = -sy * x + cy * z;
    const y2 = cp * y - sp * z1;
    const scale = 0.8 * Math.min(canvas.width, canvas.height) / size;
    return [canvas.width / 2 + scale * x1, canvas.height / 2 - scale * y2];
  }
  function displaced(k, phi) {
    const m = data.modes[k];
    if (!m) return data.nodes;
    const a = 0.1 * size;
    return data.nodes.map((p, n) => p.map((x, i) => {
      const re = m.shape_re[n][i], im = m.shape_im[n][i];
      return x + a * (re * Math.cos(phi) - im * Math.sin(phi));
    }));
  }
  function lines(points, colour, width) {
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.beginPath();
    data.edges.forEach(([i, j]) => {
      const a = project(points[i]), b = project(points[j]);
      ctx.moveTo(a[0], a[1]);
      ctx.lineTo(b[0], b[1]);
    });
    ctx.stroke();
    ctx.fillStyle = colour;
    points.forEach((p) => { const q = project(p); ctx.fillRect(q[0] - 2, q[1] - 2, 4, 4); });
  }
  function render(now) {
    if (running) phase = 2 * Math.PI * ((now - t0) / 2000);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    lines(data.nodes, "#bbbbbb", 1);
    lines(displaced(Number(select.value), phase), "#1f77b4", 2.5);
    document.body.dataset.status = "ok";
  }
  function frame(now) {
    render(now);
    requestAnimationFrame(frame);
  }
  let drag = null;
  canvas.addEventListener("mousedown", (e) => { drag = [e.clientX, e.clientY]; });
  window.addEventListener("mouseup", () => { drag = null; });
  window.addEventListener("mousemove", (e) => {
    if (!drag) return;
    yaw += (e.clientX - drag[0]) * 0.01;
    pitch += (e.clientY - drag[1]) * 0.01;
    drag = [e.clientX, e.clientY];
  });
  play.addEventListener("click", () => { running = !running; play.textContent = running ? "pause" : "play"; });
  // A first frame now, so that a page read without animation frames (a headless
  // screenshot) shows the first mode; then one per display frame.
  render(t0 + 250);
  requestAnimationFrame(frame);
})();
