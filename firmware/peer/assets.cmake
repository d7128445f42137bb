# The peer scenes' meshes and texture as flash arrays, made by lineraster-asset at build time from
# tests/data/peer (included by firmware/peer and tests/firmware_host, which build the same
# program): the bunny fitted to [-1,1]^3 by its bounding box (its normals area-weighted by the OBJ
# loader), the same bunny in spatial order (--locality: for the small-RAM program, small_ram.cpp,
# whose vertex cache needs it), the bunny subdivided twice (also in spatial order), the cube with the baboon in RGB565, the ground plane
# (which samples the cube's texture).
include(${PROJECT_SOURCE_DIR}/firmware/host_tools.cmake)
lr_asset_header(peer_bunny_asset tests/data/peer/bunny.obj --fit-box --fine-positions)
lr_asset_header(peer_bunny_local_asset tests/data/peer/bunny.obj --fit-box --locality --fine-positions)
lr_asset_header(peer_bunnyx_asset tests/data/peer/bunny.obj --fit-box --subdivide 2 --fine-positions)
lr_asset_header(peer_bunnyx_local_asset tests/data/peer/bunny.obj --fit-box --subdivide 2 --locality
               --fine-positions)
lr_asset_header(peer_cube_asset tests/data/peer/cube.obj --texture tests/data/peer/baboon.png)
lr_asset_header(peer_ground_asset tests/data/peer/ground.obj)
# lr_bench's 64,000-triangle knot (knot64k_gouraud) in spatial order, for the small-RAM program.
lr_asset_header(knot64k_local_asset tests/host/data/torus_knot.obj --fit --subdivide 2 --locality)
set(LR_PEER_ASSET_HEADERS ${peer_bunny_asset_HEADER} ${peer_bunnyx_asset_HEADER}
    ${peer_cube_asset_HEADER} ${peer_ground_asset_HEADER})
