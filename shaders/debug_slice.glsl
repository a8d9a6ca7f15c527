// The debug slices of a volume (vct.slice, sdf.slice, hddagi.occupancy) share one frame: the slice
// is square, centred in the image (cells stay square whatever the aspect), and marked on three
// sides with what it shows. The bottom edge is the slice's horizontal axis and the left edge its
// vertical one, each in its axis's colour (x red, y green, z blue, the usual gizmo colours); along
// the top edge a bar in the cut axis's colour is filled to the slice's position along that axis.
// The horizontal and vertical axes are the two the cut leaves, in x, y, z order.

ivec2 sliceAxes(int cut) { return cut == 0 ? ivec2(1, 2) : (cut == 1 ? ivec2(0, 2) : ivec2(0, 1)); }

vec3 axisColour(int axis) { return axis == 0 ? vec3(1.0, 0.1, 0.1) : (axis == 1 ? vec3(0.1, 1.0, 0.1) : vec3(0.2, 0.4, 1.0)); }

// The point of the volume ([0, 1]^3) at slice coordinates uv on the cut at `position`.
vec3 slicePoint(int cut, float position, vec2 uv) {
    ivec2 axes = sliceAxes(cut);
    vec3 p = vec3(0.0);
    p[cut] = position;
    p[axes.x] = uv.x;
    p[axes.y] = uv.y;
    return p;
}

// True when `pixel` shows the slice, with uv in [0, 1)^2 (x along the horizontal axis, y up);
// false with `frame` the margin's colour there (black, or a marker's).
bool slicePixel(ivec2 pixel, ivec2 size, int cut, float position, out vec2 uv, out vec3 frame) {
    int side = min(size.x, size.y);
    int band = max(side / 48, 1);
    int inner = max(side - 2 * band, 1);
    ivec2 p = pixel - (size - ivec2(side)) / 2;
    ivec2 q = p - ivec2(band);
    uv = (vec2(q) + 0.5) / float(inner);
    frame = vec3(0.0);
    if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(inner)))) return true;
    bool alongX = q.x >= 0 && q.x < inner, alongY = q.y >= 0 && q.y < inner;
    ivec2 axes = sliceAxes(cut);
    if (alongX && p.y >= 0 && q.y < 0) frame = axisColour(axes.x);
    else if (alongY && p.x >= 0 && q.x < 0) frame = axisColour(axes.y);
    else if (alongX && q.y >= inner && p.y < side && uv.x < clamp(position, 0.0, 1.0)) frame = axisColour(cut);
    return false;
}
