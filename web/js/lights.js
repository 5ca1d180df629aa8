// Where each light's marker sits on a panel, and where a marker dragged to a
// point of the panel puts its light.
//
// A marker shows the direction the light comes from, seen by the camera: on
// a circle of radius RADIUS × the panel's width about the panel's centre, a
// light straight behind the camera sits at the centre, one beside the model
// on the circle; a light behind the model is drawn hollow. Point and
// directional lights are placed alike (a point light by the direction of its
// position from the model's centre, the origin of the normalised model), so
// that every light stays in reach, even a point light behind the camera
// (the default one is). Dragging a marker turns its light about the model's
// centre: a point light keeps its distance, a directional light its length.

/** The circle of directions, as a fraction of the panel's width. */
export const RADIUS = 0.42;

/** The unit direction towards `light` from the model's centre, in world space. */
export function towards(light) {
  const v = light.kind === 'point' ? light.position : light.direction.map((x) => -x);
  const n = Math.hypot(...v);
  return n > 0 ? v.map((x) => x / n) : [0, 0, 1];
}

/** `d` in eye space: the rotation of the column-major view matrix `m`. */
function toEye(m, d) {
  return [0, 1, 2].map((i) => m[i] * d[0] + m[4 + i] * d[1] + m[8 + i] * d[2]);
}

/** `v` from eye space back to world space (the rotation's transpose). */
function toWorld(m, v) {
  return [0, 1, 2].map((j) => m[4 * j] * v[0] + m[4 * j + 1] * v[1] + m[4 * j + 2] * v[2]);
}

/**
 * The markers of `lights` on a panel of `width` × `height` image pixels seen
 * through view matrix `view`: [{k, x, y, behind}] for the lights that are on.
 */
export function markerPositions(lights, view, width, height) {
  if (!view) return [];
  const r = RADIUS * Math.min(width, height);
  const out = [];
  lights.forEach((light, k) => {
    if (!light.on) return;
    const [x, y, z] = toEye(view, towards(light));
    // Seen from the camera, towards the viewer is +z in eye space.
    out.push({ k, x: width / 2 + r * x, y: height / 2 - r * y, behind: z < 0 });
  });
  return out;
}

/**
 * `light` turned so that its marker sits at image point (`px`, `py`) of a
 * panel of `width` × `height`: the direction keeps its side (in front of or
 * behind the model); beyond the circle it lies in the plane of the screen.
 */
export function dragLight(light, view, width, height, px, py) {
  const r = RADIUS * Math.min(width, height);
  let x = (px - width / 2) / r;
  let y = -(py - height / 2) / r;
  const rr = x * x + y * y;
  let z = 0;
  if (rr > 1) {
    const n = Math.sqrt(rr);
    x /= n;
    y /= n;
  } else {
    const side = toEye(view, towards(light))[2] < 0 ? -1 : 1;
    z = side * Math.sqrt(1 - rr);
  }
  const d = toWorld(view, [x, y, z]);
  const round = (v) => v.map((c) => Number(c.toFixed(3)));
  if (light.kind === 'point') {
    const distance = Math.hypot(...light.position) || 1;
    return { ...light, position: round(d.map((c) => c * distance)) };
  }
  const length = Math.hypot(...light.direction) || 1;
  return { ...light, direction: round(d.map((c) => -c * length)) };
}
