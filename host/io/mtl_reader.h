/* SPDX-License-Identifier: MIT */
/* mtl_reader.h: C++, internal to the OBJ loader (obj_loader.cc, mtl_reader.cc); the C API is
 * obj_loader.h. Reads an OBJ's mtllib files for tinyobjloader, keeps what tinyobj::material_t
 * cannot tell, and copies the materials into ObjMaterial. Also the file, path and warning helpers
 * both files use. Nothing here is called from C, so exceptions may pass: obj_load catches them. */
#ifndef PT_MTL_READER_H
#define PT_MTL_READER_H

#ifndef __cplusplus
#error "io/mtl_reader.h is C++ (obj_loader.cc and mtl_reader.cc only)"
#endif

#include <tiny_obj_loader.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

/* error.h is C11; its _Noreturn has the C++11 spelling [[noreturn]]. */
#define _Noreturn [[noreturn]]
extern "C" {
#include "base/error.h"
#include "io/mesh.h"
}
#undef _Noreturn

namespace mtl_reader {

/* What tinyobj::material_t cannot tell: whether illum, Tf, Ns, Pr and Pm were given, and the
 * MTL file (its texture paths are resolved inside its folder). */
struct MaterialExtras {
    std::string file;
    bool has_illum, has_tf, has_ns = false, has_pr = false, has_pm = false;
    explicit MaterialExtras(const std::string &file_, bool has_illum_ = true, bool has_tf_ = true)
        : file(file_), has_illum(has_illum_), has_tf(has_tf_)
    {
    }
};

/* Silences the warnings about unused statements and texture options (obj_loader_set_quiet,
 * obj_loader.cc). */
extern bool quiet_unused;

/* Reads each mtllib from the OBJ's folder, warning (default material) when it is missing. One that
 * exists but cannot be read as a material library (a folder, /dev/zero, too large) is an error,
 * kept in `error` for the loader to report after tinyobjloader returns. */
class MaterialLibraryReader : public tinyobj::MaterialReader {
  public:
    explicit MaterialLibraryReader(const std::string &folder) : error(), folder_(folder) {}
    std::vector<MaterialExtras> extras; /* parallel to the materials appended */
    Error error;

    bool operator()(const std::string &name, std::vector<tinyobj::material_t> *materials,
                    std::map<std::string, int> *names, std::string *warnings,
                    std::string *errors) override;

  private:
    std::string folder_;
};

/* One tinyobjloader material as an ObjMaterial: absent illum -1, absent Tf 1 1 1, texture paths
 * resolved inside the MTL's folder (fs_resolve_inside: one that leaves it is an error naming the
 * MTL, the material and the statement, unless --allow-outside-paths). */
bool copy_material(const tinyobj::material_t &from, const MaterialExtras &extras, ObjMaterial *to,
                   Error *err);

/* The folder part of a path ("" for none, "/" for the root) and a name resolved against one. */
std::string folder_of(const std::string &path);
std::string join_path(const std::string &folder, const std::string &name);
/* The whole file as a string: a regular file under `limit` bytes only (input_file.h). */
bool read_whole_file(const char *path, const char *kind, size_t limit, std::string *text,
                     Error *err);
/* tinyobjloader's messages, one warning a line, naming `source`; lines repeating what obj_lines
 * or MaterialLibraryReader already said are dropped. */
void warn_lines(const std::string &source, const std::string &text);

} // namespace mtl_reader

#endif
