// fluid-demo — the tuning panel (see tuning_panel.h).
#include "demo/tuning_panel.h"

#include "demo/ui_common.h"

#include <fluid/error.h>

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <string_view>

namespace fluid::demo {

namespace {
using namespace ui;

// Errors of the panel's fields by ImGui id, shown in red under the field until it takes a value.
// Demo UI state, one panel per process like ImGui's own context; forgotten when another level
// is shown or the level restarts (its clock goes back).
struct FieldErrors {
    const Level* level = nullptr;
    std::string file;
    double lastTime = 0.0;
    std::map<ImGuiID, std::string> messages;
};

FieldErrors& fieldErrors(const Level& level) {
    static FieldErrors errors;
    const double now = level.world.time();
    if (errors.level != &level || errors.file != level.file || now < errors.lastTime) {
        errors.messages.clear();
        errors.level = &level;
        errors.file = level.file;
    }
    errors.lastTime = now;
    return errors;
}

// Runs `apply` (a setter that may throw fluid::Error) and records or clears the field's error.
template <class F> void applyField(FieldErrors& errors, ImGuiID id, F&& apply) {
    try {
        apply();
        errors.messages.erase(id);
    } catch (const Error& e) {
        errors.messages[id] = e.what();
    }
}

void showFieldError(const FieldErrors& errors, ImGuiID id) {
    const auto it = errors.messages.find(id);
    if (it != errors.messages.end()) {
        ImGui::PushStyleColor(ImGuiCol_Text, kRed);
        ImGui::TextWrapped("%s", it->second.c_str());
        ImGui::PopStyleColor();
    }
}

void rangeTooltip(std::string_view description, std::string_view unit, double lo, double hi) {
    if (!ImGui::IsItemHovered()) {
        return;
    }
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 24.0f);
    text(description);
    ImGui::PopTextWrapPos();
    ImGui::TextDisabled("unit: %.*s   range [%g, %g]", static_cast<int>(unit.size()), unit.data(),
                        lo, hi);
    ImGui::TextDisabled("drag, or Ctrl + click to type");
    ImGui::EndTooltip();
}

// Drag speed per pixel: a fraction of the value, so small and large parameters both tune
// smoothly (the speed follows the value as it is dragged: a logarithmic feel).
float dragSpeed(double value, double lo, double hi) {
    const double magnitude = std::abs(value);
    const double speed = magnitude > 0.0 ? 0.005 * magnitude : std::min(1e-3 * (hi - lo), 0.01);
    return static_cast<float>(std::max(speed, 1e-7));
}

// The DragScalar format: the value with up to 5 significant digits, then the unit.
std::string valueFormat(std::string_view unit) {
    std::string format = "%.5g";
    if (!unit.empty() && unit != "1") {
        format += ' ';
        for (const char c : unit) {
            format += c;
            if (c == '%') {
                format += '%';
            }
        }
    }
    return format;
}

// Dragging stays within [lo, hi]; a value typed with Ctrl + click is not clamped but passed on,
// so that the library's own error (which names the range and unit) explains a refusal.
constexpr ImGuiSliderFlags kFieldFlags = ImGuiSliderFlags_NoRoundToFormat;

// A drag field for a double in [lo, hi]; true when the user changed it.
bool dragDouble(const char* label, double& value, double lo, double hi, std::string_view unit) {
    const std::string format = valueFormat(unit);
    return ImGui::DragScalar(label, ImGuiDataType_Double, &value, dragSpeed(value, lo, hi), &lo,
                             &hi, format.c_str(), kFieldFlags);
}

// The sum of the world's force.gravity plugins, given to Box2D as the loader does, so that
// bodies fall and float with the fluid's gravity. Sleeping bodies would not notice: wake them.
void syncBox2dGravity(Level& level) {
    if (!level.physics) {
        return;
    }
    double gx = 0.0;
    double gy = 0.0;
    for (const auto& force : level.world.forces()) {
        if (force->type() == "force.gravity") {
            gx += force->param("gx");
            gy += force->param("gy");
        }
    }
    level.physics->SetGravity(b2Vec2(static_cast<float>(gx), static_cast<float>(gy)));
    for (b2Body* body = level.physics->GetBodyList(); body != nullptr; body = body->GetNext()) {
        if (body->GetType() != b2_staticBody) {
            body->SetAwake(true);
        }
    }
}

// Name the level file gave the plugin, or its type.
std::string pluginName(const Level& level, PluginKind kind, uint32_t index, const Plugin& plugin) {
    for (const Level::PluginEntry& entry : level.plugins) {
        if (entry.kind == kind && entry.index == index) {
            return entry.name;
        }
    }
    return std::string(plugin.type());
}

void pluginSection(Level& level, Plugin& plugin, PluginKind kind, uint32_t index,
                   FieldErrors& errors) {
    const std::string name = pluginName(level, kind, index, plugin);
    std::string header = name;
    if (name != plugin.type()) {
        header += "  (" + std::string(plugin.type()) + ")";
    }
    header += "###plugin";
    ImGui::PushID(&plugin);
    if (ImGui::CollapsingHeader(header.c_str())) {
        const std::span<const ParamDecl> decls = plugin.params();
        if (decls.empty()) {
            ImGui::TextDisabled("no parameters");
        }
        for (const ParamDecl& decl : decls) {
            const std::string label(decl.name);
            if (decl.type == ParamType::Points) {
                ImGui::TextDisabled("%s: %zu points", label.c_str(),
                                    plugin.points(decl.name).size());
                rangeTooltip(decl.description, decl.unit, decl.minValue, decl.maxValue);
                continue;
            }
            const ImGuiID id = ImGui::GetID(label.c_str());
            double value = plugin.param(decl.name);
            if (dragDouble(label.c_str(), value, decl.minValue, decl.maxValue, decl.unit)) {
                applyField(errors, id, [&] {
                    plugin.setParam(decl.name, value);
                    if (plugin.type() == "force.gravity") {
                        syncBox2dGravity(level);
                    }
                });
            }
            rangeTooltip(decl.description, decl.unit, decl.minValue, decl.maxValue);
            showFieldError(errors, id);
        }
    }
    ImGui::PopID();
}

// A field's label in the panel: its key in words ("yieldStress" -> "yield stress").
std::string fieldLabel(std::string_view name) {
    std::string label;
    for (const char c : name) {
        if (c >= 'A' && c <= 'Z') {
            label += ' ';
            label += char(c - 'A' + 'a');
        } else {
            label += c;
        }
    }
    return label;
}

void solverSection(Level& level, FieldErrors& errors) {
    World& world = level.world;
    if (!ImGui::CollapsingHeader("Solver", ImGuiTreeNodeFlags_DefaultOpen)) {
        return;
    }
    const WorldDef& def = world.def();
    if (def.solver == Solver::PositionBased) {
        ImGui::TextDisabled("position-based fluids [Macklin & Mueller 2013]");
        PositionBasedDef pb = def.positionBased;
        const ImGuiID id = ImGui::GetID("solver");
        bool changed = false;
        // The named presets (levels with floating bodies name precise: docs/box2d.md, "Which
        // preset").
        if (ImGui::Button("game")) {
            pb = positionBasedPreset(Quality::Game);
            pb.vorticity = def.positionBased.vorticity;
            changed = true;
        }
        ImGui::SameLine();
        if (ImGui::Button("precise")) {
            pb = positionBasedPreset(Quality::Precise);
            pb.vorticity = def.positionBased.vorticity;
            changed = true;
        }
        ImGui::SameLine();
        ImGui::TextDisabled("quality presets");
        for (const Field<PositionBasedDef>& field : positionBasedFields()) {
            const std::string label = fieldLabel(field.name);
            if (field.whole != nullptr) {
                const auto lo = static_cast<uint32_t>(field.lo);
                const auto hi = static_cast<uint32_t>(field.hi);
                changed |= ImGui::DragScalar(label.c_str(), ImGuiDataType_U32, &(pb.*field.whole),
                                             0.05f, &lo, &hi, "%u", kFieldFlags);
            } else {
                const auto lo = static_cast<float>(field.lo);
                const auto hi = static_cast<float>(field.hi);
                changed |= ImGui::DragScalar(label.c_str(), ImGuiDataType_Float, &(pb.*field.real),
                                             0.002f, &lo, &hi, "%.3f", kFieldFlags);
            }
            rangeTooltip(field.description, field.unit, field.lo, field.hi);
        }
        if (changed) {
            applyField(errors, id, [&] { world.setPositionBased(pb); });
        }
        showFieldError(errors, id);
    } else {
        ImGui::TextDisabled("explicit SPH: sub-steps from the CFL condition");
    }
    // With bodies the coupling steps the world one sub-step at a time; its profile sums the
    // frame (the world's holds only the last round).
    const Profile& profile = level.coupling ? level.coupling->profile() : world.profile();
    ImGui::Text("last frame: %u sub-steps, %.2f ms", profile.substeps,
                static_cast<double>(profile.step));
    if (ImGui::TreeNode("stages (ms)")) {
        for (const StageTime& stage : profile.stageTimes()) {
            ImGui::Text("%-15s %7.3f", stage.name, static_cast<double>(stage.ms));
        }
        ImGui::TreePop();
    }
    ImGui::Text("compression: max %.2f%%, mean %.2f%%",
                100.0 * static_cast<double>(profile.densityErrorMax),
                100.0 * static_cast<double>(profile.densityErrorAvg));
    if (profile.speedClamped > 0) {
        ImGui::TextColored(kAmber, "speed cap hit by %u particles", profile.speedClamped);
    }
}

// The field's description with both presets' values ("... Water 3.5, yoghurt 20.").
std::string fieldTooltip(const MaterialField& field) {
    char presets[96];
    std::snprintf(presets, sizeof presets, " Water %g, yoghurt %g.", field.get(water()),
                  field.get(yoghurt()));
    return std::string(field.description) + presets;
}

void materialSection(World& world, const std::string& name, MaterialId id, FieldErrors& errors) {
    ImGui::PushID(static_cast<int>(id.index));
    const std::string header = "material: " + name + "###material";
    if (ImGui::CollapsingHeader(header.c_str())) {
        for (const MaterialField& field : materialFields()) {
            if (field.name == "kernelParticles") {
                continue; // informational: the step never reads it
            }
            const std::string label = fieldLabel(field.name);
            const ImGuiID fieldId = ImGui::GetID(label.c_str());
            Material material = world.material(id);
            float& value = material.*field.real;
            // An open lower end (mass, rest density, stiffness) gets a small positive floor.
            const auto lo = static_cast<float>(field.openLow ? field.hi * 1e-12 : field.lo);
            const auto hi = static_cast<float>(field.hi);
            const std::string format = valueFormat(field.unit);
            const float speed = static_cast<float>(dragSpeed(value, lo, hi));
            if (ImGui::DragScalar(label.c_str(), ImGuiDataType_Float, &value, speed, &lo, &hi,
                                  format.c_str(), kFieldFlags)) {
                applyField(errors, fieldId, [&] { world.setMaterial(id, material); });
            }
            rangeTooltip(fieldTooltip(field), field.unit, lo, hi);
            showFieldError(errors, fieldId);
        }
        ImGui::TextDisabled("spacing %.4f m", static_cast<double>(world.spacing(id)));
    }
    ImGui::PopID();
}

void sectionTitle(const char* title) {
    ImGui::Spacing();
    ImGui::TextDisabled("%s", title);
    ImGui::Separator();
}

} // namespace

void drawTuningPanel(Level& level, bool* open) {
    if (open == nullptr || !*open) {
        return;
    }
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(
        ImVec2(viewport->WorkPos.x + viewport->WorkSize.x - 10.0f, viewport->WorkPos.y + 10.0f),
        ImGuiCond_FirstUseEver, ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(360.0f, std::min(viewport->WorkSize.y - 20.0f, 680.0f)),
                             ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Tuning (Tab)", open, ImGuiWindowFlags_NoSavedSettings)) {
        FieldErrors& errors = fieldErrors(level);
        ImGui::PushItemWidth(-150.0f);
        solverSection(level, errors);

        World& world = level.world;
        const auto forces = world.forces();
        if (!forces.empty()) {
            sectionTitle("Forces");
            for (std::size_t i = 0; i < forces.size(); ++i) {
                pluginSection(level, *forces[i], PluginKind::Force, static_cast<uint32_t>(i),
                              errors);
            }
        }
        const auto boundaries = world.boundaries();
        if (!boundaries.empty()) {
            sectionTitle("Boundaries");
            for (std::size_t i = 0; i < boundaries.size(); ++i) {
                pluginSection(level, *boundaries[i], PluginKind::Boundary, static_cast<uint32_t>(i),
                              errors);
            }
        }
        if (!level.materials.empty()) {
            sectionTitle("Materials");
            for (const auto& [name, id] : level.materials) {
                materialSection(world, name, id, errors);
            }
        }
        ImGui::PopItemWidth();
    }
    ImGui::End();
}

} // namespace fluid::demo
