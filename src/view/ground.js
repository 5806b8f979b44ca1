// ==== the ground's rocks, footprints and sunk footpads (a page with rocks or regolith)
// Spliced into viewer.html by view/mod.rs where the trace has them. D.rocks: [x, y, z, r]
// per rock (the base's centre in I on the ground, the hemisphere's radius); D.footprints:
// {leg, t (lift-off), p (centre on the ground), depth_m}; D.regolith: footpads sink, and
// D.sinkage_m[k][i] is leg k's sinkage at time i (0 above the ground or on a rock).
const ROCKS = (Array.isArray(D.rocks) ? D.rocks : []).filter(Array.isArray)
  .map((r) => ({ c: vec(r), r: num(r[3]) })).filter((r) => ok3(r.c) && r.r > 0);
const PRINTS = (Array.isArray(D.footprints) ? D.footprints : []).filter((f) => f && typeof f === 'object')
  .map((f) => ({ leg: Math.floor(num(f.leg)), t: num(f.t), p: vec(f.p), depth: num(f.depth_m) }))
  .filter((f) => ok3(f.p) && fin(f.t));
const REGOLITH = D.regolith === true;
const SINK = (Array.isArray(D.sinkage_m) ? D.sinkage_m : []).map((a) => (Array.isArray(a) ? a : []));
let hoverAt = null; // the projection, pose and scale last drawn, for hover
/** A rock's outline in I: its dome's silhouette from side to side over the top, then the
 *  near half of its base. */
function rockOutline(rk, V) {
  const w = unit(cross(normal, V), G.u);
  let up = unit(cross(V, w), normal); if (dot(up, normal) < 0) up = mul(up, -1);
  let near = cross(normal, w); if (dot(near, V) < 0) near = mul(near, -1);
  const out = [];
  for (let k = 0; k <= 24; k++) {
    const a = Math.PI * k / 12, d = k <= 12 ? add(mul(w, Math.cos(a)), mul(up, Math.sin(a)))
      : sub(mul(w, Math.cos(a)), mul(near, Math.sin(a)));
    out.push(add(rk.c, mul(d, rk.r)));
  }
  return out;
}
/** Draws a rock on ctx through the projection P: its outline filled with a shading lit from
 *  LIGHT (brightest where the dome faces the light). */
function drawRock(ctx, rk, P, s, V) {
  const pts = rockOutline(rk, V).map(P);
  const lit = dot(LIGHT, normal) > 0 ? LIGHT : normal;
  const h = P(add(rk.c, mul(lit, 0.6 * rk.r))), R = Math.max(1, 1.3 * rk.r * s);
  const gr = ctx.createRadialGradient(h[0], h[1], 0, h[0], h[1], R);
  gr.addColorStop(0, 'rgb(214,208,199)'); gr.addColorStop(1, 'rgb(92,86,80)');
  ctx.beginPath(); pts.forEach((p, k) => (k ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]))); ctx.closePath();
  ctx.fillStyle = gr; ctx.fill();
  ctx.strokeStyle = 'rgba(40,32,24,0.55)'; ctx.lineWidth = 1; ctx.stroke();
}
/** Every rock onto the ground's layer, far to near. */
function groundRocks(g, A, ox, oy, s) {
  const { R, U, V } = cam;
  const P = (p) => { const r = sub(p, A); return [ox + dot(r, R) * s, oy - dot(r, U) * s, dot(r, V)]; };
  ROCKS.map((rk) => ({ rk, z: P(rk.c)[2] })).sort((a, b) => a.z - b.z).forEach(({ rk }) => drawRock(g, rk, P, s, V));
}
/** Leg k's footpad sinks now: its depth below the ground, or 0. */
function sinkage(k) {
  const d = num((SINK[k] || [])[idx]);
  return REGOLITH && d > 0 ? d : 0;
}
/** The rocks near the lander again (in depth order with its parts), the footprints left by
 *  now, and each sunk footpad veiled by the ground, with its hole. */
function groundPrims(prims, poly, P, ps, s) {
  hoverAt = { P, ps, s };
  const V = cam.V, C = P(ps.cg), reach2 = reach * s + 4;
  for (const rk of ROCKS) {
    const c = P(rk.c), size = rk.r * s;
    if (Math.abs(c[0] - C[0]) > reach2 + size || Math.abs(c[1] - C[1]) > reach2 + size) continue;
    prims.push({ z: c[2], f: () => drawRock(vctx, rk, P, s, V) });
  }
  const ring = (c, r) => { const out = []; for (let a = 0; a < 20; a++) { const th = a * Math.PI / 10; out.push(P(add(c, add(mul(G.u, r * Math.cos(th)), mul(G.v, r * Math.sin(th)))))); } return out; };
  for (const f of PRINTS) {
    if (f.t > T[idx]) continue;
    poly(ring(f.p, padR), 'rgba(38,30,22,0.5)', 'rgba(20,16,12,0.6)', P(f.p)[2] - padR);
  }
  // A sunk footpad seen through the soil: its disc and the strut below the ground veiled
  // in the ground's colour, and the hole's opening at the surface over them.
  const veil = 'rgba(150,136,118,0.72)', tw = Math.max(2.5, 0.028 * s);
  legs.forEach((l, k) => {
    const d = sinkage(k), foot = footAt(k, ps);
    if (!(d > 0) || !foot || !ok3(l.hip)) return;
    const top = add(foot, mul(normal, d)), F = P(foot);
    const disc = ring(foot, padR);
    prims.push({ z: F[2] - 0.5 * padR + 1e-6, f: () => {
      vctx.beginPath(); disc.forEach((p, n) => (n ? vctx.lineTo(p[0], p[1]) : vctx.moveTo(p[0], p[1]))); vctx.closePath();
      vctx.fillStyle = veil; vctx.fill();
    } });
    // Where the strut from the hip enters the ground (heights along the normal; the ground
    // there is taken at the footpad's, `top`).
    const hip = add(ps.cg, qrot(ps.q, l.hip)), hh = dot(sub(hip, top), normal);
    const entry = hh > 0 ? add(hip, mul(sub(foot, hip), hh / (hh + d))) : hip, E = P(entry);
    prims.push({ z: Math.max(E[2], F[2]) + 1e-6, f: () => {
      vctx.strokeStyle = veil; vctx.lineWidth = tw + 2; vctx.lineCap = 'butt';
      vctx.beginPath(); vctx.moveTo(E[0], E[1]); vctx.lineTo(F[0], F[1]); vctx.stroke();
    } });
    const hole = ring(top, padR);
    prims.push({ z: Math.max(P(top)[2], E[2], F[2]) + 2e-6, f: () => {
      vctx.beginPath(); hole.forEach((p, n) => (n ? vctx.lineTo(p[0], p[1]) : vctx.moveTo(p[0], p[1]))); vctx.closePath();
      vctx.fillStyle = 'rgba(38,30,22,0.75)'; vctx.fill(); vctx.strokeStyle = 'rgba(20,16,12,0.9)'; vctx.lineWidth = 1; vctx.stroke();
    } });
  });
}
/** What is under the pointer at (x, y): a footpad (its sinkage or height), a footprint (its
 *  depth) or a rock (its radius); '' for nothing. */
function hoverText(x, y) {
  if (!hoverAt) return '';
  const { P, ps, s } = hoverAt, near = (p, r) => { const q = P(p); return Math.hypot(q[0] - x, q[1] - y) <= Math.max(6, r * s); };
  const cm = (m) => (100 * m).toFixed(m < 0.1 ? 2 : 1) + ' cm';
  for (let k = 0; k < legs.length; k++) {
    const foot = footAt(k, ps);
    if (!foot || !near(foot, padR)) continue;
    const d = at(`leg${k}_penetration_m`, idx), sunk = sinkage(k);
    if (sunk > 0) return `footpad ${k}: sunk ${cm(sunk)}`;
    if (!fin(d)) return `footpad ${k}`;
    return d > 0 ? `footpad ${k}: in contact, ${cm(d)} deep` : `footpad ${k}: ${cm(-d)} above the ground`;
  }
  for (const f of PRINTS) if (f.t <= T[idx] && near(f.p, padR)) return `footprint of footpad ${f.leg}: ${cm(f.depth)} deep`;
  let best = null;
  for (const rk of ROCKS) {
    const q = P(add(rk.c, mul(normal, 0.4 * rk.r))), dd = Math.hypot(q[0] - x, q[1] - y);
    if (dd <= rk.r * s && (!best || q[2] > best.z)) best = { rk, z: q[2] };
  }
  return best ? `rock: radius ${fmt(best.rk.r)} m (${fmt(2 * best.rk.r)} m across and ${fmt(best.rk.r)} m high)` : '';
}
view.addEventListener('pointermove', (e) => {
  if (drag) return;
  const r = view.getBoundingClientRect(), txt = hoverText(e.clientX - r.left, e.clientY - r.top);
  view.title = txt; window.touchdownHover = txt;
});

