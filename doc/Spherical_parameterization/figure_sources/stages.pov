// The paper's Figure 1: the stages of the map with uniform weights. Each row follows one half of the mesh:
// top, half A (its faces coloured by the input's normals, B grey), its planar disk, and the spheres seen from +z;
// bottom, half B seen from the back, its disk mirrored (seen from below, as the southern hemisphere is), and the
// spheres seen from -z. The black line is the cut loop shared by the two halves: the unit circle, then the
// equator of the initial sphere.

#version 3.7;

#declare Columns = 4;
#declare Rows = 2;
#include "layout.inc"
#include "input.inc"
#include "stages.inc"
#include "final_uniform.inc"

#declare Loop_radius = 0.008;
#declare Edge_radius = 0.0025;

Column_title("(a) two halves", Mesh_figures, Loop_figures, 0)
Column_title("(b) planar disks", "uniform (Tutte) weights", "loop on the unit circle", 1)
Column_title("(c) initial sphere", "Moebius + stereographic", Initial_figures, 2)
Column_title("(d) final sphere", Final_uniform_status, Final_uniform_figures, 3)

union {
  object { Half_a } object { Half_b_plain texture { Grey } } object { Input_loop(Loop_radius) texture { Loop_ink } }
  translate Cell_centre(0, 0)
}
union {
  object { Half_b } object { Half_a_plain texture { Grey } } object { Input_loop(Loop_radius) texture { Loop_ink } }
  rotate 180 * y translate Cell_centre(0, 1)
}

union {
  object { Disk_a finish { Unlit } } object { Disk_a_edges(Edge_radius) texture { Ink } }
  object { Disk_loop(Loop_radius) texture { Ink } }
  translate Cell_centre(1, 0)
}
union {
  object { Disk_b finish { Unlit } } object { Disk_b_edges(Edge_radius) texture { Ink } }
  object { Disk_loop(Loop_radius) texture { Ink } scale <-1, 1, 1> }
  translate Cell_centre(1, 1)
}

#macro Both_sides(Object, Loop, C)
  union { object { Object } object { Loop texture { Loop_ink } } translate Cell_centre(C, 0) }
  union { object { Object } object { Loop texture { Loop_ink } } rotate 180 * y translate Cell_centre(C, 1) }
#end
Both_sides(Initial_sphere, Sphere_loop(Loop_radius), 2)
Both_sides(Final_uniform, Final_uniform_loop(Loop_radius), 3)

Cell_caption("half A, from the front", 0, 0)
Cell_caption("half B, from the back", 0, 1)
Cell_caption("disk A", 1, 0)
Cell_caption("disk B, seen from below", 1, 1)
#for(C, 2, 3)
  Cell_caption("seen from +z", C, 0)
  Cell_caption("seen from -z", C, 1)
#end
