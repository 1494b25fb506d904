-- Every gr command and argument form of the A4 language and the report's manual, in one
-- small scene (tests render it from the command line and through Blender's importer).

root = gr.node('root')

-- gr.material with 3, 4, 5 and 6 arguments; gr.texture with its 6
matte = gr.material({0.7, 0.6, 0.5}, {0.3, 0.3, 0.3}, 20)
mirror = gr.material({0.2, 0.2, 0.25}, {0.8, 0.8, 0.8}, 100, 0.6)
shiny = gr.material({0.1, 0.5, 0.2}, {0.9, 0.9, 0.9}, 200, 0.2, 1.0)
glass = gr.material({0.0, 0.0, 0.0}, {0.9, 0.9, 0.9}, 300, 0.0, 1.0, 1.53)
red = gr.material({0.8, 0.1, 0.1}, {0.5, 0.5, 0.5}, 25)
blue = gr.material({0.1, 0.2, 0.8}, {0.5, 0.5, 0.5}, 25)
checker = gr.texture('checker.png', {0.2, 0.2, 0.2}, 10, 0.0, 1.0, 1.0)

-- A joint is a plain node; transforms apply in call order, rotate's axis in either case
arm = gr.joint('arm', {-90, 0, 90}, {-45, 0, 45})
root:add_child(arm)
arm:rotate('Y', 15)
arm:rotate('x', -10)
arm:translate(0, 0.2, 0)

-- Hierarchical primitives
ball = gr.sphere('sphere')
ball:scale(0.7, 0.7, 0.7)
ball:translate(-3.2, 2.0, 0)
ball:set_texture(checker)
arm:add_child(ball)

cube = gr.cube('cube')
cube:rotate('z', 30)
cube:translate(-1.6, 1.6, 0)
cube:set_material(matte)
arm:add_child(cube)

cylinder = gr.cylinder('cylinder')
cylinder:scale(0.5, 0.6, 0.5)
cylinder:translate(0.5, 2.2, 0)
cylinder:set_material(shiny)
arm:add_child(cylinder)

cone = gr.cone('cone')
cone:scale(0.6, 0.6, 0.6)
cone:translate(2.2, 1.4, 0)
cone:set_material(red)
arm:add_child(cone)

torus = gr.torus('torus')
torus:scale(0.12, 0.12, 0.12)
torus:rotate('X', -60)
torus:translate(3.6, 2.2, 0)
torus:set_material(blue)
root:add_child(torus)

-- Non-hierarchical primitives
local plain = {
    gr.nh_sphere('nh_sphere', {-3.2, -0.3, 0}, 0.7),
    gr.nh_box('nh_box', {-2.1, -0.9, -0.5}, 1.1),
    gr.nh_cylinder('nh_cylinder', {0.1, -0.3, 0}, 0.5, 1.3),
    gr.nh_cone('nh_cone', {1.6, -1.0, 0}, 0.5, 1.4),
    gr.nh_torus('nh_torus', {3.3, -0.3, 0}, 0.6, 0.25),
}
for _, shape in ipairs(plain) do
    shape:set_material(matte)
    root:add_child(shape)
end

-- Meshes: an OBJ file, and A4's older form with listed vertices and faces
box = gr.mesh('obj box', 'box.obj')
box:scale(0.45, 0.45, 0.45)
box:rotate('y', 35)
box:translate(-3.2, -2.6, 0)
box:set_material(mirror)
root:add_child(box)

tetra = gr.mesh('listed tetrahedron', {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}})
tetra:translate(-1.9, -3.0, 0)
tetra:set_material(blue)
root:add_child(tetra)

-- CSG: every operation, a nested tree and a transformed CSG node
a = gr.nh_sphere('a', {0, 0, 0}, 0.6)
b = gr.nh_box('b', {-0.45, -0.45, -0.45}, 0.9)
a:set_material(red)
b:set_material(blue)
meet = gr.csg(a, b, 'intersection')
meet:translate(0.0, -2.6, 0)
root:add_child(meet)

c = gr.cylinder('c')
c:scale(0.3, 0.8, 0.3)
d = gr.cylinder('d')
d:scale(0.3, 0.8, 0.3)
d:rotate('z', 90)
cross = gr.csg(c, d, 'union')
e = gr.nh_sphere('e', {0, 0, 0.1}, 0.35)
cut = gr.csg(cross, e, 'diff')
cut:set_material(matte)
cut:rotate('y', 25)
cut:translate(1.7, -2.6, 0)
root:add_child(cut)

glass_ball = gr.nh_sphere('glass ball', {3.4, -2.5, 0.5}, 0.6)
glass_ball:set_material(glass)
root:add_child(glass_ball)

floor = gr.cube('floor')
floor:translate(-0.5, -1, -0.5)
floor:scale(14, 0.2, 8)
floor:translate(0, -3.4, -1)
floor:set_material(matte)
root:add_child(floor)

-- gr.light with 3 arguments (point) and 5 (area)
key = gr.light({-4, 8, 10}, {0.6, 0.6, 0.6}, {1, 0, 0})
sky = gr.light({2, 12, 6}, {0.5, 0.5, 0.5}, {1, 0, 0}, 4, 3)

-- gr.render with 15 arguments: recursion, supersampling, shadow rays, depth of field
gr.render(root, 'every_command.png', 48, 36,
          {0, 1, 14}, {0, -0.1, -1}, {0, 1, 0}, 40,
          {0.25, 0.25, 0.25}, {key, sky},
          4, 1, 4, 14, 0.02)
