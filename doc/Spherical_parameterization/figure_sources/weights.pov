// The paper's Figures 2-3: final spheres for uniform, mean-value and cotangent weights, every vertex coloured by
// the input's normal there. Top row: the input from the front and the spheres seen from +z (the side of disk A);
// bottom row: the input from the back and the spheres seen from -z. The black line is the cut loop of stage 1.
// Rendered by scripts/make_figures.sh with +L pointing at one mesh's folder of generated include files.

#version 3.7;

#declare Columns = 4;
#declare Rows = 2;
#include "layout.inc"
#include "input.inc"
#include "final_uniform.inc"
#include "final_mean_value.inc"
#include "final_cotangent.inc"

#declare Loop_radius = 0.006;

#macro Both_sides(Object, Loop, C)
  union { object { Object } object { Loop texture { Loop_ink } } translate Cell_centre(C, 0) }
  union { object { Object } object { Loop texture { Loop_ink } } rotate 180 * y translate Cell_centre(C, 1) }
#end

Column_title("input mesh", Mesh_figures, "colour: its normals", 0)
Column_title("uniform weights", Final_uniform_status, Final_uniform_figures, 1)
Column_title("mean-value weights", Final_mean_value_status, Final_mean_value_figures, 2)
Column_title("cotangent weights", Final_cotangent_status, Final_cotangent_figures, 3)

Both_sides(Input_mesh, Input_loop(1.6 * Loop_radius), 0)
Both_sides(Final_uniform, Final_uniform_loop(Loop_radius), 1)
Both_sides(Final_mean_value, Final_mean_value_loop(Loop_radius), 2)
Both_sides(Final_cotangent, Final_cotangent_loop(Loop_radius), 3)

Cell_caption("front", 0, 0)
Cell_caption("back", 0, 1)
#for(C, 1, 3)
  Cell_caption("seen from +z", C, 0)
  Cell_caption("seen from -z", C, 1)
#end
