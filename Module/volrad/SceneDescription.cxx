// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/SceneDescription.h"

#include "volrad/Error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <sstream>

namespace volrad {

namespace {

using json = nlohmann::json;

[[noreturn]] void fail(const std::string& key, const std::string& what)
{
  throw Error("scene file: " + key + " " + what);
}

void allowOnly(const json& obj, const std::string& where, std::initializer_list<const char*> keys)
{
  if (!obj.is_object()) {
    fail(where.empty() ? std::string("the top level") : where, "must be an object");
  }
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool known = false;
    for (const char* k : keys) {
      known = known || it.key() == k;
    }
    if (!known) {
      std::string allowed;
      for (const char* k : keys) {
        allowed += (allowed.empty() ? "" : ", ") + std::string(k);
      }
      fail("key '" + (where.empty() ? "" : where + ".") + it.key() + "'",
           "is unknown (allowed here: " + allowed + ")");
    }
  }
}

double number(const json& j, const std::string& key)
{
  if (!j.is_number()) {
    fail(key, "must be a number");
  }
  const double v = j.get<double>();
  if (!std::isfinite(v)) {
    fail(key, "must be finite");
  }
  return v;
}

std::string text(const json& j, const std::string& key)
{
  if (!j.is_string()) {
    fail(key, "must be a string");
  }
  return j.get<std::string>();
}

ChannelValues channelValues(const json& j, const std::string& key, int channels)
{
  if (j.is_number()) {
    return uniformChannels(number(j, key));
  }
  if (!j.is_array() || int(j.size()) != channels) {
    fail(key,
         "must be a number or an array of " + std::to_string(channels) +
           " numbers (one per channel)");
  }
  ChannelValues v{ 0, 0, 0 };
  for (int c = 0; c < channels; ++c) {
    v[c] = number(j[c], key + "[" + std::to_string(c) + "]");
  }
  if (channels == 1) {
    v = uniformChannels(v[0]);
  }
  return v;
}

Vec3 vec3(const json& j, const std::string& key)
{
  if (!j.is_array() || j.size() != 3) {
    fail(key, "must be an array of 3 numbers");
  }
  return Vec3(number(j[0], key + "[0]"), number(j[1], key + "[1]"), number(j[2], key + "[2]"));
}

BoundaryCondition boundaryCondition(const json& j, const std::string& key, int channels)
{
  allowOnly(j, key, { "type", "radiance", "reflectance", "emission" });
  BoundaryCondition bc;
  const std::string type = j.contains("type") ? text(j["type"], key + ".type") : "open";
  if (type == "open") {
    if (j.contains("reflectance") || j.contains("emission")) {
      fail(key, "is open: reflectance and emission belong to walls");
    }
    if (j.contains("radiance")) {
      bc.radiance = channelValues(j["radiance"], key + ".radiance", channels);
    }
  } else if (type == "wall") {
    bc.type = BoundaryCondition::Type::Wall;
    if (j.contains("radiance")) {
      fail(key, "is a wall: radiance belongs to open faces");
    }
    if (j.contains("reflectance")) {
      bc.reflectance = channelValues(j["reflectance"], key + ".reflectance", channels);
    }
    if (j.contains("emission")) {
      bc.emission = channelValues(j["emission"], key + ".emission", channels);
    }
  } else {
    fail(key + ".type", "is '" + type + "', expected 'open' or 'wall'");
  }
  return bc;
}

void parseArrays(const json& j, ArrayNames& a)
{
  allowOnly(j,
            "arrays",
            { "absorption",
              "scattering",
              "surface_scattering",
              "emission",
              "surface_emission",
              "normals" });
  const std::pair<const char*, ArrayBinding*> keys[] = { { "absorption", &a.absorption },
                                                         { "scattering", &a.scattering },
                                                         { "surface_scattering",
                                                           &a.surfaceScattering },
                                                         { "emission", &a.emission },
                                                         { "surface_emission", &a.surfaceEmission },
                                                         { "normals", &a.normals } };
  for (const auto& [key, binding] : keys) {
    if (j.contains(key)) {
      binding->name = text(j[key], std::string("arrays.") + key);
      binding->required = true;
      if (binding->name.empty()) {
        fail(std::string("arrays.") + key, "must not be empty");
      }
    }
  }
}

void parseLights(const json& j, SceneDescription& d)
{
  if (!j.is_array()) {
    fail("lights", "must be an array");
  }
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string key = "lights[" + std::to_string(i) + "]";
    const json& l = j[i];
    if (!l.is_object() || !l.contains("type")) {
      fail(key, "must be an object with a 'type'");
    }
    const std::string type = text(l["type"], key + ".type");
    if (type == "directional") {
      allowOnly(l, key, { "type", "direction", "irradiance" });
      DirectionalLight dl;
      if (l.contains("direction")) {
        dl.direction = vec3(l["direction"], key + ".direction");
      }
      if (!(dl.direction.stableNorm() > 0.0)) {
        fail(key + ".direction", "must not be zero");
      }
      if (l.contains("irradiance")) {
        dl.irradiance = channelValues(l["irradiance"], key + ".irradiance", d.channels);
      }
      d.directionalLights.push_back(dl);
    } else if (type == "point") {
      allowOnly(l, key, { "type", "position", "intensity" });
      PointLight pl;
      if (!l.contains("position")) {
        fail(key, "needs a 'position'");
      }
      pl.position = vec3(l["position"], key + ".position");
      if (l.contains("intensity")) {
        pl.intensity = channelValues(l["intensity"], key + ".intensity", d.channels);
      }
      d.pointLights.push_back(pl);
    } else {
      fail(key + ".type", "is '" + type + "', expected 'directional' or 'point'");
    }
  }
}

/// [[x, y], ...] (or [[x, r, g, b], ...] with `columns` 4) into functions.
void transferFunctions(const json& j,
                       const std::string& key,
                       TransferFunction* out,
                       int outputs,
                       bool allowGrey)
{
  if (!j.is_array() || j.empty()) {
    fail(key, "must be a non-empty array of [scalar, value] points");
  }
  for (int c = 0; c < outputs; ++c) {
    out[c].points.clear();
  }
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string at = key + "[" + std::to_string(i) + "]";
    const json& p = j[i];
    const bool grey = p.is_array() && p.size() == 2 && allowGrey;
    if (!p.is_array() || (!grey && int(p.size()) != outputs + 1)) {
      fail(at,
           outputs == 1 ? "must be [scalar, value]"
                        : "must be [scalar, red, green, blue]" +
                            std::string(allowGrey ? " or [scalar, value]" : ""));
    }
    const double x = number(p[0], at + "[0]");
    for (int c = 0; c < outputs; ++c) {
      out[c].points.emplace_back(
        x, number(p[grey ? 1 : c + 1], at + "[" + std::to_string(grey ? 1 : c + 1) + "]"));
    }
  }
}

void parseMaterial(const json& j, MaterialSettings& m)
{
  allowOnly(j,
            "material",
            { "scalars",
              "preset",
              "extinction",
              "albedo",
              "color",
              "emission",
              "surface_gradient",
              "rescale_slope",
              "rescale_intercept",
              "relative",
              "per_voxel",
              "labels" });
  if (j.contains("scalars")) {
    m.scalars = text(j["scalars"], "material.scalars");
  }
  // A preset first; the other keys replace its parts.
  if (j.contains("preset")) {
    m.preset = text(j["preset"], "material.preset");
    try {
      m.map = materialPreset(m.preset);
    } catch (const Error& e) {
      fail("material.preset", std::string("names an ") + e.what());
    }
  }
  if (j.contains("extinction")) {
    transferFunctions(j["extinction"], "material.extinction", &m.map.extinction, 1, false);
  }
  if (j.contains("albedo")) {
    transferFunctions(j["albedo"], "material.albedo", &m.map.albedo, 1, false);
  }
  if (j.contains("color")) {
    transferFunctions(j["color"], "material.color", m.map.color.data(), kMaxChannels, false);
  }
  if (j.contains("emission")) {
    transferFunctions(
      j["emission"], "material.emission", m.map.emission.data(), kMaxChannels, true);
  }
  if (j.contains("surface_gradient")) {
    m.map.surfaceGradient = number(j["surface_gradient"], "material.surface_gradient");
  }
  if (j.contains("rescale_slope")) {
    m.map.rescaleSlope = number(j["rescale_slope"], "material.rescale_slope");
  }
  if (j.contains("rescale_intercept")) {
    m.map.rescaleIntercept = number(j["rescale_intercept"], "material.rescale_intercept");
  }
  if (j.contains("labels")) {
    const json& t = j["labels"];
    if (!t.is_object() || t.empty()) {
      fail("material.labels", "must be an object of label materials, keyed by label number");
    }
    for (auto it = t.begin(); it != t.end(); ++it) {
      const std::string key = "material.labels." + it.key();
      std::size_t used = 0;
      long long label = 0;
      try {
        label = std::stoll(it.key(), &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != it.key().size()) {
        fail("material.labels key '" + it.key() + "'", "must be a whole number (a label)");
      }
      allowOnly(it.value(), key, { "extinction", "albedo", "color", "emission" });
      if (!it.value().contains("extinction")) {
        fail(key, "needs an 'extinction'");
      }
      LabelMaterial lm;
      lm.extinction = number(it.value()["extinction"], key + ".extinction");
      if (it.value().contains("albedo")) {
        lm.albedo = number(it.value()["albedo"], key + ".albedo");
      }
      if (it.value().contains("color")) {
        lm.color = channelValues(it.value()["color"], key + ".color", kMaxChannels);
      }
      if (it.value().contains("emission")) {
        lm.emission = channelValues(it.value()["emission"], key + ".emission", kMaxChannels);
      }
      m.map.labels[label] = lm;
    }
    // A label table replaces a preset's functions.
    if (!j.contains("extinction")) {
      m.map.extinction.points.clear();
    }
  }
  for (const char* flag : { "relative", "per_voxel" }) {
    if (j.contains(flag)) {
      if (!j[flag].is_boolean()) {
        fail(std::string("material.") + flag, "must be true or false");
      }
      (std::string(flag) == "relative" ? m.map.relative : m.map.perVoxel) = j[flag].get<bool>();
    }
  }
  const bool any = j.contains("albedo") || j.contains("color") || j.contains("emission") ||
                   j.contains("surface_gradient");
  if (any && !m.map.active()) {
    fail("material", "needs an 'extinction' (or a 'preset') for its other functions to apply");
  }
  try {
    validateMaterial(m.map, "material");
  } catch (const Error& e) {
    throw Error(std::string("scene file: ") + e.what());
  }
}

void parseSolver(const json& j, SolverSettings& s)
{
  allowOnly(j, "solver", { "method", "epsilon", "max_iterations" });
  if (j.contains("method")) {
    s.method = text(j["method"], "solver.method");
    if (s.method != "hierarchical" && s.method != "dense") {
      fail("solver.method", "is '" + s.method + "', expected 'hierarchical' or 'dense'");
    }
  }
  if (j.contains("epsilon")) {
    s.epsilon = number(j["epsilon"], "solver.epsilon");
    if (s.epsilon <= 0.0) {
      fail("solver.epsilon", "must be > 0");
    }
  }
  if (j.contains("max_iterations")) {
    const json& m = j["max_iterations"];
    if (!m.is_number_integer() || m.get<long long>() < 1) {
      fail("solver.max_iterations", "must be an integer >= 1");
    }
    s.maxIterations = m.get<long long>();
  }
}

} // namespace

void SceneDescription::applyTo(Scene& scene) const
{
  scene.channels = channels;
  scene.boundary = boundary;
  scene.directionalLights = directionalLights;
  scene.pointLights = pointLights;
}

SceneDescription parseSceneDescription(const std::string& jsonText)
{
  json j;
  try {
    j = json::parse(jsonText);
  } catch (const json::exception& e) {
    // parse_error, and also out_of_range for a number beyond double's range
    // (found by Testing/Fuzz/FuzzSceneFile: "1E99999900").
    throw Error(std::string("scene file: malformed JSON: ") + e.what());
  }
  allowOnly(j, "", { "version", "channels", "arrays", "material", "boundary", "lights", "solver" });
  SceneDescription d;
  if (!j.contains("version")) {
    fail("'version'", "is missing (this reader knows version 1)");
  }
  if (!j["version"].is_number_integer() || j["version"].get<long long>() != 1) {
    fail("version", "must be 1");
  }
  if (j.contains("channels")) {
    const json& c = j["channels"];
    if (!c.is_number_integer() || (c.get<long long>() != 1 && c.get<long long>() != 3)) {
      fail("channels", "must be 1 or 3");
    }
    d.channels = c.get<int>();
  }
  if (j.contains("arrays")) {
    parseArrays(j["arrays"], d.arrays);
  }
  if (j.contains("material")) {
    parseMaterial(j["material"], d.material);
  }
  if (j.contains("boundary")) {
    const json& b = j["boundary"];
    allowOnly(b, "boundary", { "default", "xmin", "xmax", "ymin", "ymax", "zmin", "zmax" });
    BoundaryCondition def;
    if (b.contains("default")) {
      def = boundaryCondition(b["default"], "boundary.default", d.channels);
    }
    for (int f = 0; f < kFaceCount; ++f) {
      const char* name = faceName(Face(f));
      d.boundary[f] = b.contains(name)
                        ? boundaryCondition(b[name], std::string("boundary.") + name, d.channels)
                        : def;
    }
  }
  if (j.contains("lights")) {
    parseLights(j["lights"], d);
  }
  if (j.contains("solver")) {
    parseSolver(j["solver"], d.solver);
  }
  return d;
}

SceneDescription readSceneDescription(const std::string& path)
{
  std::ifstream in(path);
  if (!in) {
    throw Error("cannot read the scene file '" + path + "'");
  }
  std::ostringstream s;
  s << in.rdbuf();
  try {
    return parseSceneDescription(s.str());
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
}

} // namespace volrad
