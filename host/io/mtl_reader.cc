// SPDX-License-Identifier: MIT
/* The MTL side of the OBJ loader (mtl_reader.h): tinyobjloader reads the material libraries
 * through MaterialLibraryReader, which also scans each one for the keys tinyobj::material_t does
 * not record as given; copy_material turns the result into ObjMaterial. */
#include "io/mtl_reader.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>
#include <sys/stat.h>

extern "C" {
#include "base/fs.h"
#include "io/input_file.h"
}

namespace mtl_reader {

bool quiet_unused = false;

namespace {

/* The statements pt's material mapping reads (README "Materials"); any other is warned about. */
const std::set<std::string> &used_statements()
{
    static const std::set<std::string> used = {
        "newmtl", "Kd", "Ks", "Ke", "Ni", "d", "Tr", "Tf", "Kt", "illum", "Ns", "Pr", "Pm",
        "map_Kd", "map_Ke", "map_Pr", "map_Pm", "map_d", "norm", "map_Bump", "map_bump", "bump"};
    return used;
}

/* Statements pt does not use but that need no word: the ambient colour and its map (Ka, map_Ka)
 * are a rasterizer's fill that nearly every exporter writes; a path tracer's ambient is the light
 * itself. Warning about them on almost every MTL hid the warnings that matter. */
bool is_harmless_statement(const std::string &name) { return name == "Ka" || name == "map_Ka"; }

bool is_texture_statement(const std::string &name)
{
    return name.compare(0, 4, "map_") == 0 || name == "bump" || name == "norm" || name == "disp" ||
           name == "decal" || name == "refl";
}

/* Statement and texture option names pt does not use, each with how often it occurs. */
struct UnusedNames {
    std::map<std::string, int> statements, options;
};

/* The texture options of a texture statement's arguments ("-s 2 2 1 -bm 0.5 file.png"); -bm is
 * used on normal maps only. A token like "-0.5" is a value, not an option. */
void note_texture_options(const std::string &name, std::istringstream &args, UnusedNames *unused)
{
    bool bump = name == "norm" || name == "bump" || name == "map_Bump" || name == "map_bump";
    std::string token;
    while (args >> token) {
        if (token.size() < 2 || token[0] != '-' || isdigit((unsigned char)token[1]) || token[1] == '.')
            continue;
        if (!(bump && token == "-bm"))
            unused->options[token + " (" + name + ")"]++;
    }
}

/* A name as it may be printed: at most 40 characters, bytes outside printable ASCII as '?'. */
std::string printable(const std::string &name)
{
    std::string out = name.substr(0, 40);
    for (char &c : out)
        if (c < 0x20 || c > 0x7e)
            c = '?';
    return name.size() > 40 ? out + "..." : out;
}

/* Warns once per statement name and per texture option of one MTL file; a file full of junk gets
 * the first 16 names and a count of the rest, not a warning per junk line. */
void warn_unused(const std::string &path, const UnusedNames &unused)
{
    const int limit = 16;
    int shown = 0, rest = 0;
    if (quiet_unused)
        return;
    for (const auto &s : unused.statements) {
        if (shown++ >= limit) {
            rest++;
            continue;
        }
        warn("%s: statement '%s' is not used by pt (ignored %d time%s)", path.c_str(),
             printable(s.first).c_str(), s.second, s.second == 1 ? "" : "s");
    }
    for (const auto &o : unused.options) {
        if (shown++ >= limit) {
            rest++;
            continue;
        }
        warn("%s: texture option %s is not used by pt (ignored %d time%s)", path.c_str(),
             printable(o.first).c_str(), o.second, o.second == 1 ? "" : "s");
    }
    if (rest > 0)
        warn("%s: %d more statements or texture options not used by pt", path.c_str(), rest);
}

/* Which materials of one MTL gave illum and Tf/Kt, in the order tinyobj::LoadMtl appends them: a
 * block is appended when the next newmtl starts if it has a name, and the last block always. */
std::vector<MaterialExtras> scan_material_blocks(const std::string &text, const std::string &file,
                                                 UnusedNames *unused)
{
    struct Block {
        bool named;
        MaterialExtras extras;
    };
    std::vector<Block> blocks(1, Block{false, MaterialExtras(file, false, false)});
    std::string unix_text = text; /* tinyobjloader also ends lines at a lone \r */
    std::replace(unix_text.begin(), unix_text.end(), '\r', '\n');
    std::istringstream lines(unix_text);
    std::string line;
    while (std::getline(lines, line)) {
        size_t begin = line.find_first_not_of(" \t");
        size_t end = line.find_last_not_of(" \t\r");
        if (begin == std::string::npos || end == std::string::npos)
            continue;
        std::string record = line.substr(begin, end + 1 - begin);
        auto keyword = [&record](const char *word) {
            size_t n = strlen(word);
            return record.size() > n && record.compare(0, n, word) == 0 &&
                   (record[n] == ' ' || record[n] == '\t');
        };
        if (keyword("newmtl")) {
            blocks.push_back(Block{record.size() > 7, MaterialExtras(file, false, false)});
        } else if (keyword("illum")) {
            blocks.back().extras.has_illum = true;
        } else if (keyword("Tf") || keyword("Kt")) {
            blocks.back().extras.has_tf = true;
        } else if (keyword("Ns")) {
            blocks.back().extras.has_ns = true;
        } else if (keyword("Pr")) {
            blocks.back().extras.has_pr = true;
        } else if (keyword("Pm")) {
            blocks.back().extras.has_pm = true;
        }
        if (record[0] == '#')
            continue;
        std::istringstream words(record);
        std::string name;
        words >> name;
        if (!used_statements().count(name) && !is_harmless_statement(name))
            unused->statements[name]++;
        else if (is_texture_statement(name))
            note_texture_options(name, words, unused);
    }
    std::vector<MaterialExtras> appended;
    for (size_t i = 0; i < blocks.size(); i++)
        if (blocks[i].named || i + 1 == blocks.size())
            appended.push_back(blocks[i].extras);
    return appended;
}

} // namespace

std::string folder_of(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    if (slash == std::string::npos)
        return "";
    return slash == 0 ? "/" : path.substr(0, slash);
}

std::string join_path(const std::string &folder, const std::string &name)
{
    if (folder.empty() || name.empty() || name[0] == '/')
        return name;
    return folder[folder.size() - 1] == '/' ? folder + name : folder + "/" + name;
}

bool read_whole_file(const char *path, const char *kind, size_t limit, std::string *text,
                     Error *err)
{
    char *data = NULL;
    size_t size = 0;
    if (!input_file_read(path, kind, limit, &data, &size, err))
        return false;
    try {
        text->assign(data, size);
    } catch (...) {
        free(data);
        throw;
    }
    free(data);
    return true;
}

/* tinyobjloader's messages are '\n'-separated (one is "...found\n."): each line becomes one
 * warning. Lines repeating what obj_lines or MaterialLibraryReader already said are dropped. */
void warn_lines(const std::string &source, const std::string &text)
{
    static const char *const already_reported[] = {"Degenerated face found",
                                                   "Failed to load material file(s)"};
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        size_t begin = line.find_first_not_of(" \t\r.");
        if (begin == std::string::npos)
            continue;
        line = line.substr(begin, line.find_last_not_of(" \t\r") + 1 - begin);
        bool repeated = false;
        for (const char *known : already_reported)
            repeated = repeated || line.compare(0, strlen(known), known) == 0;
        if (!repeated)
            warn("%s: %s", source.c_str(), line.c_str());
    }
}

bool MaterialLibraryReader::operator()(const std::string &name,
                                       std::vector<tinyobj::material_t> *materials,
                                       std::map<std::string, int> *names,
                                       std::string *warnings, std::string *errors)
{
    (void)warnings; /* ours go straight to warn(), naming the MTL */
    std::string path = join_path(folder_, name);
    std::string text;
    Error read_error = {};
    if (!read_whole_file(path.c_str(), "a material library", INPUT_LIMIT_MTL, &text,
                         &read_error)) {
        if (read_error.code == ERR_FILE_MISSING)
            warn("material library %s not found: its materials are replaced by the default",
                 path.c_str());
        else
            error_set(&error, read_error.code, path.c_str(), 0, "%s", read_error.message);
        return false;
    }
    size_t before = materials->size();
    std::istringstream stream(text);
    std::string mtl_warnings;
    tinyobj::LoadMtl(names, materials, &stream, &mtl_warnings, errors);
    warn_lines(path, mtl_warnings);
    UnusedNames unused;
    std::vector<MaterialExtras> found = scan_material_blocks(text, path, &unused);
    warn_unused(path, unused);
    if (found.size() != materials->size() - before) /* keep tinyobj's values as they are */
        found.assign(materials->size() - before, MaterialExtras(path));
    extras.insert(extras.end(), found.begin(), found.end());
    return true;
}

/* A texture path resolved inside the MTL's folder into a 1024-byte field ("" when none). A map
 * written on Windows (`map_Kd .\\SpiderTex.jpg`, `textures\\wood.png`): when the path as written
 * names no file, its backslashes are taken as separators (a file name with a backslash in it is
 * rare; an MTL exported on Windows is not), and that path too must stay inside the folder. */
static bool copy_path(const char *material, const char *statement, const std::string &file,
                      const std::string &name, char out[1024], Error *err)
{
    out[0] = '\0';
    if (name.empty())
        return true;
    char what[256];
    snprintf(what, sizeof what, "material '%s' %s", material, statement);
    char path[4096];
    Error resolve_error = {};
    if (!fs_resolve_inside(file.c_str(), name.c_str(), what, path, sizeof path, &resolve_error)) {
        if (resolve_error.code == ERR_PATH_ESCAPES) {
            *err = resolve_error;
            return false;
        }
        path[0] = '\0'; /* too long: warned below */
    }
    struct stat st;
    if (path[0] && name.find('\\') != std::string::npos && stat(path, &st) != 0) {
        std::string slashed = name;
        std::replace(slashed.begin(), slashed.end(), '\\', '/');
        char candidate[4096];
        if (!fs_resolve_inside(file.c_str(), slashed.c_str(), what, candidate, sizeof candidate,
                               err))
            return false;
        if (stat(candidate, &st) == 0)
            snprintf(path, sizeof path, "%s", candidate);
    }
    if (!path[0] || strlen(path) >= 1024)
        warn("material %s: %s path longer than 1023 characters ignored", material, statement);
    else
        snprintf(out, 1024, "%s", path);
    return true;
}

bool copy_material(const tinyobj::material_t &from, const MaterialExtras &extras, ObjMaterial *to,
                   Error *err)
{
    snprintf(to->name, sizeof to->name, "%s", from.name.c_str());
    for (int c = 0; c < 3; c++) {
        to->kd[c] = from.diffuse[c];
        to->ks[c] = from.specular[c];
        to->ke[c] = from.emission[c];
        to->tf[c] = extras.has_tf ? from.transmittance[c] : 1.0f;
    }
    to->ni = from.ior;
    to->d = from.dissolve;
    to->illum = extras.has_illum ? from.illum : -1;
    to->ns = from.shininess;
    to->pr = from.roughness;
    to->pm = from.metallic;
    to->has_ns = extras.has_ns;
    to->has_pr = extras.has_pr;
    to->has_pm = extras.has_pm;
    /* DESIGN: norm, else map_Bump / bump, is the normal map; -bm scales its xy. */
    bool norm = !from.normal_texname.empty();
    to->bump_scale = norm ? from.normal_texopt.bump_multiplier : from.bump_texopt.bump_multiplier;
    snprintf(to->normal_statement, sizeof to->normal_statement, "%s", norm ? "norm" : "map_Bump");
    const std::string &file = extras.file;
    return copy_path(to->name, "map_Kd", file, from.diffuse_texname, to->map_kd, err) &&
           copy_path(to->name, "map_Ke", file, from.emissive_texname, to->map_ke, err) &&
           copy_path(to->name, "map_Pr", file, from.roughness_texname, to->map_pr, err) &&
           copy_path(to->name, "map_Pm", file, from.metallic_texname, to->map_pm, err) &&
           copy_path(to->name, "map_d", file, from.alpha_texname, to->map_d, err) &&
           copy_path(to->name, to->normal_statement, file,
                     norm ? from.normal_texname : from.bump_texname, to->map_normal, err);
}

} // namespace mtl_reader
