-- The examples of the report's manual, with its own values: the y-aligned cylinder and cone,
-- the torus, glass (outer index 1, inner 1.53), a texture, the CSG of a sphere and a cube
-- built before it is added to a parent, a 50 x 50 area light, and gr.render in its 13- and
-- 15-argument forms (the report prints the summaries the tests compare with).

root = gr.node('root')

glass = gr.material({0.0, 0.0, 0.0}, {0.9, 0.9, 0.9}, 100, 0.0, 1, 1.53)
stone = gr.material({0.6, 0.6, 0.6}, {0.2, 0.2, 0.2}, 10, 0.3)
waffle = gr.texture('checker.png', {0.1, 0.1, 0.1}, 10, 0, 1, 1)

cylinder = gr.cylinder('cylinder')
cylinder:scale(40, 40, 40)
cylinder:translate(-150, 0, 0)
cylinder:set_material(stone)
root:add_child(cylinder)

nh_cylinder = gr.nh_cylinder('nh_cylinder', {-60, 0, 0}, 30, 80)
nh_cylinder:set_material(glass)
root:add_child(nh_cylinder)

cone = gr.cone('cone')
cone:scale(30, 30, 30)
cone:translate(30, -40, 0)
cone:set_texture(waffle)
root:add_child(cone)

nh_cone = gr.nh_cone('nh_cone', {120, -40, 0}, 30, 80)
nh_cone:set_material(stone)
root:add_child(nh_cone)

torus = gr.torus('torus')
torus:scale(6, 6, 6)
torus:translate(-100, 120, 0)
torus:set_material(stone)
root:add_child(torus)

nh_torus = gr.nh_torus('nh_torus', {80, 120, 0}, 35, 10)
nh_torus:set_material(stone)
root:add_child(nh_torus)

-- "Firstly define a sphere and a cube without adding them as children of any node, then
-- use gr.csg(sphere, cube, 'intersection') and add the CSG node to the parent"
sphere = gr.nh_sphere('sphere', {0, 0, 0}, 50)
cube = gr.nh_box('cube', {-40, -40, -40}, 80)
sphere:set_material(stone)
cube:set_material(stone)
intersection = gr.csg(sphere, cube, 'intersection')
intersection:translate(0, -150, 0)
root:add_child(intersection)

point = gr.light({-200, 300, 400}, {0.5, 0.5, 0.5}, {1, 0, 0})
area = gr.light({0, 100, 400}, {0.9, 0.9, 0.9}, {1, 0, 0}, 50, 50)

gr.render(root, 'report_manual.png', 500, 500,
          {0, 0, 800}, {0, 0, -1}, {0, 1, 0}, 50,
          {0.3, 0.3, 0.3}, {area},
          50, 1, 40)

gr.render(root, 'report_manual_dof.png', 500, 500,
          {0, 0, 800}, {0, 0, -1}, {0, 1, 0}, 50,
          {0.3, 0.3, 0.3}, {area},
          50, 1, 40, 300, 20)
