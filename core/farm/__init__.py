"""Rendering on a Dask cluster: a frame's borders, or a range of frames, as tasks.

    python -m core farm SCENE.blend|SCENE.lua --scheduler tcp://HOST:8786|local
                        [--split 4x4] [--frames 1-250 [--chunk 10]] -o OUT_####.png

`jobs` plans the tasks (borders in whole pixels, frame chunks, Blender's #### names) and
knows nothing of Dask; `worker` is what runs on a worker: the real `blender -b ... -E WHITTED`
(or the CS488 command line) in a folder of its own, its output files returned as bytes;
`client` submits, follows and cancels the tasks and writes the frames (`stitch` puts a
frame's borders together). Random numbers depend only on pixel, sample and seed, so the
stitched frame is the single-machine render, bit for bit. `distributed` is imported here
only, by the farm command: rendering without a farm never needs it.
"""
