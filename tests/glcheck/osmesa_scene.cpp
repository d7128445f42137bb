#include "tests/glcheck/osmesa_scene.hpp"

#include <GL/gl.h>
#include <GL/osmesa.h>

#include <array>
#include <cmath>
#include <cstddef>

#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/support/scene_compare.hpp"

namespace lr::glcheck {
namespace {

// Column-major copy of a row-major matrix for glLoadMatrixd.
std::array<GLdouble, 16> gl_matrix(const ref::Mat4d& m) {
  std::array<GLdouble, 16> a{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) a[size_t(c * 4 + r)] = m.m[r][c];
  return a;
}

void material(GLenum what, const host::Vec3d& c) {
  const GLfloat v[4] = {GLfloat(c[0]), GLfloat(c[1]), GLfloat(c[2]), 1.0f};
  glMaterialfv(GL_FRONT_AND_BACK, what, v);
}

GLint min_filter(Filter f, MipMode mip) {
  const bool lin = f == Filter::kBilinear;
  switch (mip) {
    case MipMode::kNone:
      break;
    case MipMode::kNearest:
      return lin ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
    case MipMode::kLinear:
      return lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
  }
  return lin ? GL_LINEAR : GL_NEAREST;
}

// Uploads the core texture's levels texel for texel (storage row 0 = bottom = GL's first row).
void upload_texture(const Texture& t, const host::SceneOptions& o) {
  const int levels = o.mipmap == MipMode::kNone ? 1 : int(t.level_count);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int l = 0; l < levels; ++l) {
    const TextureLevel& lv = t.levels[size_t(l)];
    std::vector<uint8_t> texels;
    texels.reserve(size_t(lv.width) * lv.height * 3);
    for (int row = 0; row < lv.height; ++row)
      for (int col = 0; col < lv.width; ++col) {
        const Rgb8 c = host::texel_rgb8(t, l, col, row);
        texels.push_back(c.r);
        texels.push_back(c.g);
        texels.push_back(c.b);
      }
    glTexImage2D(GL_TEXTURE_2D, l, GL_RGB8, lv.width, lv.height, 0, GL_RGB, GL_UNSIGNED_BYTE,
                 texels.data());
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min_filter(o.filter, o.mipmap));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER,
                  o.filter == Filter::kBilinear ? GL_LINEAR : GL_NEAREST);
  const GLint wrap = o.wrap == Wrap::kRepeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, o.unlit ? GL_REPLACE : GL_MODULATE);
  glEnable(GL_TEXTURE_2D);
}

void set_state(const host::HostMesh& mesh, const host::SceneOptions& o, const ref::RefParams& p) {
  glViewport(0, 0, o.width, o.height);
  glDisable(GL_DITHER);
  glEnable(GL_DEPTH_TEST);
  // No depth test: every fragment passes and is still written, so that the depth buffer keeps
  // telling which pixels were covered.
  glDepthFunc(o.depth_test ? GL_LESS : GL_ALWAYS);
  glDepthMask(GL_TRUE);
  glFrontFace(GL_CCW);
  if (o.cull == Cull::kNone) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(o.cull == Cull::kBack ? GL_BACK : GL_FRONT);
  }
  glShadeModel(o.shading == Shading::kFlat ? GL_FLAT : GL_SMOOTH);
  glEnable(GL_NORMALIZE);

  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(gl_matrix(p.projection).data());
  glMatrixMode(GL_MODELVIEW);
  // Light directions are world space: give them while the modelview holds the view only.
  glLoadMatrixd(gl_matrix(p.view).data());
  if (o.unlit) {
    glDisable(GL_LIGHTING);
  } else {
    glEnable(GL_LIGHTING);
    const GLfloat ga[4] = {GLfloat(o.global_ambient[0]), GLfloat(o.global_ambient[1]),
                           GLfloat(o.global_ambient[2]), 1.0f};
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ga);
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, o.local_viewer ? GL_TRUE : GL_FALSE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_FALSE);
    glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL,
                  o.texture_object != nullptr ? GL_SEPARATE_SPECULAR_COLOR : GL_SINGLE_COLOR);
    const GLfloat white[4] = {1, 1, 1, 1};
    for (size_t i = 0; i < p.lights.size(); ++i) {
      const GLenum light = GLenum(GL_LIGHT0 + i);
      const ref::Vec3d d = ref::normalize(p.lights[i].direction);
      const GLfloat pos[4] = {GLfloat(d[0]), GLfloat(d[1]), GLfloat(d[2]), 0.0f};
      glEnable(light);
      glLightfv(light, GL_POSITION, pos);
      glLightfv(light, GL_AMBIENT, white);
      glLightfv(light, GL_DIFFUSE, white);
      glLightfv(light, GL_SPECULAR, white);
    }
    material(GL_AMBIENT, o.material.ambient);
    material(GL_DIFFUSE, o.material.diffuse);
    material(GL_SPECULAR, o.material.specular);
    material(GL_EMISSION, o.material.emission);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, GLfloat(o.material.shininess));
  }
  glLoadMatrixd(gl_matrix(ref::mul(p.view, p.model)).data());
  if (o.texture_object != nullptr && mesh.has_uvs()) upload_texture(*o.texture_object, o);
}

void draw(const host::HostMesh& mesh, const host::SceneOptions& o) {
  const bool colors = o.unlit && mesh.has_colors();
  const bool uvs = o.texture_object != nullptr && mesh.has_uvs();
  if (o.unlit && !colors) glColor3dv(o.material.diffuse.data());
  glBegin(GL_TRIANGLES);
  for (const auto& tri : mesh.triangles)
    for (uint32_t k : tri) {
      if (colors) glColor3dv(mesh.colors[k].data());
      if (uvs) glTexCoord2dv(mesh.uvs[k].data());
      glNormal3dv(mesh.normals[k].data());
      glVertex3dv(mesh.positions[k].data());
    }
  glEnd();
}

}  // namespace

bool render_gl(const host::HostMesh& mesh, const host::SceneOptions& o, GlFrame& out,
               std::string& error) {
  return render_gl(mesh, o, test::ref_params(mesh, o), out, error);
}

bool render_gl(const host::HostMesh& mesh, const host::SceneOptions& o, const ref::RefParams& p,
               GlFrame& out, std::string& error) {
  OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (ctx == nullptr) {
    error = "OSMesaCreateContextExt failed";
    return false;
  }
  const size_t n = size_t(o.width) * size_t(o.height);
  std::vector<uint8_t> buffer(4 * n);
  if (!OSMesaMakeCurrent(ctx, buffer.data(), GL_UNSIGNED_BYTE, o.width, o.height)) {
    OSMesaDestroyContext(ctx);
    error = "OSMesaMakeCurrent failed";
    return false;
  }
  const GLubyte* name = glGetString(GL_RENDERER);
  out.renderer = name != nullptr ? reinterpret_cast<const char*>(name) : "?";

  set_state(mesh, o, p);
  glClearColor(GLfloat(o.background[0]), GLfloat(o.background[1]), GLfloat(o.background[2]), 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  draw(mesh, o);
  glFinish();

  std::vector<uint8_t> rgba(4 * n);
  std::vector<GLfloat> depth(n);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, o.width, o.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glReadPixels(0, 0, o.width, o.height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  const GLenum gl_error = glGetError();
  OSMesaDestroyContext(ctx);
  if (gl_error != GL_NO_ERROR) {
    error = "GL error " + std::to_string(gl_error);
    return false;
  }

  out.width = o.width;
  out.height = o.height;
  out.rgb.assign(3 * n, 0);
  out.covered.assign(n, 0);
  for (int y = 0; y < o.height; ++y) {
    const size_t src = size_t(o.height - 1 - y) * size_t(o.width);  // GL rows are bottom-up
    const size_t dst = size_t(y) * size_t(o.width);
    for (size_t x = 0; x < size_t(o.width); ++x) {
      for (size_t k = 0; k < 3; ++k) out.rgb[3 * (dst + x) + k] = rgba[4 * (src + x) + k];
      out.covered[dst + x] = depth[src + x] < 1.0f;
    }
  }
  return true;
}

}  // namespace lr::glcheck
