// The page's default scene (480×480, the teapot, one point light), as TOML: what
// engine.mjs and part.mjs draw, with the model, method and yaw replaced.
export const SCENE = `[model]
source = "teapot"
normals = "auto"

[ambient]
color = [255, 255, 255]
intensity = 0.2

[[lights]]
kind = "point"
position = [2.0, 2.0, 3.0]
color = [255, 255, 255]
intensity = 1.0
attenuation = [1.0, 0.0, 0.0]

[material]
ka = [200, 60, 60]
kd = [200, 60, 60]
ks = [255, 255, 255]
shininess = 32.0

[render]
width = 480
height = 480
shading = "flat"
background = [0, 0, 0]
cull_backfaces = true
gouraud_specular = false
interpolation = "perspective"
rasterizer = "tiled"
polygons = "fans"
specular = "phong"
yaw = 0.0
pitch = 0.0
zoom = 1.0
`;
