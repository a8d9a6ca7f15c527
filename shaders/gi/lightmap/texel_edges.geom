// The atlas triangles' edges, for the texels no triangle's fill reaches (lightmap_bake.cpp): each
// triangle's outline, pulled a tenth of the way towards its centroid in the atlas and on the
// surface alike (the two are one affine map, so each point stays the surface's point for its UV).
// A triangle many texels wide then draws its outline over its own fill (which overwrites it): its
// border texels stay gutters, as they were. A thin one (a sphere's pole) covers no texel centre and
// gets texels along its outline. On the edge itself, or by a corner, a texel's point would sit on a
// crease, where classify.comp's rays along the surface graze the other faces and what they find
// would depend on the unit of length.
layout(triangles) in;
layout(line_strip, max_vertices = 4) out;

in vec3 v_position[];
in vec3 v_normal[];
flat in float v_chart[];
out vec3 g_position;
out vec3 g_normal;
flat out float g_chart;

const float INWARD = 0.1;

void main() {
    vec4 centre = (gl_in[0].gl_Position + gl_in[1].gl_Position + gl_in[2].gl_Position) / 3.0;
    vec3 centrePosition = (v_position[0] + v_position[1] + v_position[2]) / 3.0;
    for (int k = 0; k < 4; ++k) {
        int i = k % 3;
        gl_Position = mix(gl_in[i].gl_Position, centre, INWARD);
        g_position = mix(v_position[i], centrePosition, INWARD);
        g_normal = v_normal[i];
        g_chart = v_chart[0];
        EmitVertex();
    }
    EndPrimitive();
}
