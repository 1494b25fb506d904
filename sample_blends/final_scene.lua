-- The report's final scene as a CS488 script (the same layout as final_scene.blend, which
-- sample_blends/final_scene.py builds): a wooden table (a box minus an ellipsoid), a mug and
-- a bowl (a cylinder minus a smaller one), an ice-cream cone with a waffle texture and a
-- scoop on two white tori, Newell's teapot smooth shaded, a wooden floor and a mirror wall.
-- One 50 x 50 area light with 40 shadow rays, 3 x 3 supersampling, recursion depth 50.
--
--   python -m core render sample_blends/final_scene.lua      (or: make render SCENE=...)
--
-- y is up, as in the report; units are the report's.

local TABLE_TOP = -60
local FLOOR = -250

root = gr.node('root')

-- The room: a floor tiled with wood, a mirror for the back wall
local floor_wood = gr.texture('textures/wood_floor.png', {0.15, 0.15, 0.15}, 15)
local floor = gr.mesh('Floor', 'floor.obj')
floor:translate(0, FLOOR, 0)
floor:set_texture(floor_wood)
root:add_child(floor)

local mirror = gr.material({0.05, 0.05, 0.06}, {0.8, 0.8, 0.8}, 200, 0.85)
local wall = gr.cube('Mirror Wall')
wall:scale(3200, 1100, 20)
wall:translate(-1600, FLOOR, -420)
wall:set_material(mirror)
root:add_child(wall)

-- The table: a box with an ellipsoid carved from below, leaving legs and arches
local table_wood = gr.texture('textures/wood_table.png', {0.3, 0.3, 0.3}, 30)
local top = gr.cube('Table')
top:scale(660, TABLE_TOP - FLOOR, 380)
top:translate(-330, FLOOR, -190)
top:set_texture(table_wood)
local carve = gr.sphere('Table Carve')
carve:scale(300, 170, 250)
carve:translate(0, FLOOR, 0)
carve:set_texture(table_wood)
root:add_child(gr.csg(top, carve, 'diff'))

-- A mug and a bowl: a cylinder minus a smaller one that leaves a wall and a floor
local function cup(name, material, x, z, radius, height, wall_width, bottom)
    local body = gr.nh_cylinder(name, {x, TABLE_TOP + height / 2, z}, radius, height)
    local hollow = gr.nh_cylinder(name .. ' Hollow', {x, TABLE_TOP + bottom + height / 2, z},
                                  radius - wall_width, height)
    body:set_material(material)
    hollow:set_material(material)
    return gr.csg(body, hollow, 'diff')
end
local glaze = gr.material({0.12, 0.25, 0.65}, {0.7, 0.7, 0.7}, 80, 0.1)
root:add_child(cup('Mug', glaze, -235, 40, 45, 100, 7, 10))
local cream = gr.material({0.85, 0.8, 0.65}, {0.6, 0.6, 0.6}, 60, 0.15)
root:add_child(cup('Bowl', cream, 225, -60, 85, 45, 6, 8))

-- The ice cream: a waffle cone, apex down, in a stand of two tori, and a scoop on top
local x, z = 110, 120
local white = gr.material({0.9, 0.9, 0.9}, {0.5, 0.5, 0.5}, 40)
for _, ring in ipairs({{'Stand Lower', 6, 20, 6}, {'Stand Upper', 17, 16, 5}}) do
    local name, height, major, minor = unpack(ring)
    local torus = gr.nh_torus(name, {0, 0, 0}, major, minor)
    torus:rotate('x', 90)  -- the report's torus turns about z; this one stands on the table
    torus:translate(x, TABLE_TOP + height, z)
    torus:set_material(white)
    root:add_child(torus)
end
local apex, length = TABLE_TOP + 8, 130
local cone = gr.nh_cone('Cone', {x, apex, z}, 30, length)
cone:set_texture(gr.texture('textures/waffle.png', {0.1, 0.1, 0.1}, 10))
root:add_child(cone)
local scoop = gr.nh_sphere('Ice Cream', {x, apex + length + 14, z}, 33)
scoop:set_material(gr.material({0.95, 0.55, 0.65}, {0.4, 0.4, 0.4}, 30))
root:add_child(scoop)

-- Newell's teapot, smooth (Phong) shaded
local teapot = gr.mesh('Teapot', 'teapot.obj')
teapot:scale(36, 36, 36)
teapot:rotate('y', -30)
teapot:translate(-50, TABLE_TOP, -70)
teapot:set_material(gr.material({0.7, 0.12, 0.08}, {0.8, 0.8, 0.8}, 100, 0.1))
root:add_child(teapot)

local light = gr.light({0, 400, 400}, {0.9, 0.9, 0.9}, {1, 0, 0}, 50, 50)

gr.render(root, 'final_scene_lua.png', 500, 500,
          {0, 280, 850}, {0, -370, -870}, {0, 1, 0}, 50,
          {0.3, 0.3, 0.3}, {light},
          50, 1, 40)
