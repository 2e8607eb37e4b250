// fluid-demo — the ImGui panels (see ui.h).
#include "ui.h"

#include <fluid/error.h>

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace fluid::demo {

namespace {
const ImVec4 kAmber{1.00f, 0.72f, 0.20f, 1.0f};
const ImVec4 kGreen{0.40f, 0.92f, 0.45f, 1.0f};
const ImVec4 kRed{1.00f, 0.38f, 0.33f, 1.0f};
const ImVec4 kCyan{0.45f, 0.85f, 1.00f, 1.0f};
const ImVec4 kKey{0.62f, 0.80f, 1.00f, 1.0f};
// Labels and hints of the HUD and the banner: light enough to read over the grey walls
// through the overlays' dark backing (ImGui's own disabled grey, 0.5, is not).
const ImVec4 kHint{0.70f, 0.73f, 0.78f, 1.0f};
// Opacity of the HUD's and the banner's backing: dark enough that text stays readable over
// walls, water and yoghurt (unit: 1).
constexpr float kOverlayBackground = 0.82f;
// Size the banner title is drawn at when the bridge found no TrueType font (unit: px).
constexpr float kBannerSize = 28.0f;
// Where the HUD ends, margin included, before it was first measured (unit: px).
constexpr float kHudRight = 260.0f;
// Widest banner (unit: px; about 100 characters a line), the room the tuning panel takes on
// the right while it is open, and the margin to the window's edges.
constexpr float kBannerMaxWidth = 760.0f;
constexpr float kSideRoom = 370.0f;
constexpr float kEdge = 10.0f;
// Width the help window wraps the level's text at (unit: px; about the controls table's).
constexpr float kHelpTextWidth = 440.0f;
// Share of the window's height the level leaves free above it (unit: 1): Session::camera
// frames the level with a fifth of its height of room on top and a 5% margin, 0.26 of 1.32
// of the framed height when the height decides, more otherwise. The banner stays inside it.
constexpr float kBannerRoom = 0.19f;
// Right edge of the HUD as last drawn, margin included (unit: px); the banner keeps clear of
// it. Demo UI state, one HUD per process like ImGui's own context.
float g_hudRight = kHudRight;

constexpr ImGuiWindowFlags kOverlayFlags =
    ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
    ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoMove;

constexpr std::array<ControlHelp, 21> kControls{{
    {"S", "Cycle views: metaballs, pressure, particles"},
    {"G", "Gravity on / zero-g"},
    {"Left drag", "Push the fluid"},
    {"Right drag", "Pull the fluid"},
    {"Shift + left drag", "Grab a body"},
    {"Q / E (grabbing)", "Turn a grabbed plank"},
    {"Space", "Drop a blob of the current material"},
    {"M", "Switch material (water / yoghurt)"},
    {"L", "Laser from the cursor: where it meets the liquid, and the normal"},
    {"Ctrl + click", "Drop a crate (levels with bodies)"},
    {"R", "Reset the level"},
    {"P", "Pause / resume"},
    {". (period)", "Step one frame while paused"},
    {"N / B", "Next / previous level"},
    {"1 - 9", "Jump to a level"},
    {"Tab", "Tuning panel"},
    {"F5 / F9", "Save the level / go back to the save"},
    {"F1", "This help"},
    {"F11", "Fullscreen"},
    {"F12", "Screenshot"},
    {"Esc", "Level menu"},
}};

// An empty view may hold a null pointer, which ImGui's text functions must not get.
void text(std::string_view s) {
    if (s.empty()) {
        ImGui::TextUnformatted("");
        return;
    }
    ImGui::TextUnformatted(s.data(), s.data() + s.size());
}

float textWidth(std::string_view s) {
    return s.empty() ? 0.0f : ImGui::CalcTextSize(s.data(), s.data() + s.size()).x;
}

// Text centred in the window's remaining width.
void centredText(std::string_view s) {
    const float width = textWidth(s);
    const float avail = ImGui::GetContentRegionAvail().x;
    if (width < avail) {
        ImGui::SetCursorPosX(ImGui::GetCursorPosX() + 0.5f * (avail - width));
    }
    text(s);
}

// Draws with the banner font: `big` when it is a real large font, else the current font
// scaled up to kBannerSize times `scale`. Restores the font on destruction.
class BigFont {
public:
    BigFont(ImFont* big, float scale) {
        if (big != nullptr && big->FontSize >= 20.0f) {
            ImGui::PushFont(big);
            m_pushed = true;
            if (scale != 1.0f) {
                ImGui::SetWindowFontScale(scale);
                m_scaled = true;
            }
        } else {
            ImGui::SetWindowFontScale(scale * kBannerSize / ImGui::GetFontSize());
            m_scaled = true;
        }
    }
    ~BigFont() {
        if (m_scaled) {
            ImGui::SetWindowFontScale(1.0f);
        }
        if (m_pushed) {
            ImGui::PopFont();
        }
    }
    BigFont(const BigFont&) = delete;
    BigFont& operator=(const BigFont&) = delete;

private:
    bool m_pushed = false;
    bool m_scaled = false;
};

// ---- tuning panel -----------------------------------------------------------------------------

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

// Pushes the hint colour as ImGui's disabled text colour for the overlays' labels.
class HintColour {
public:
    HintColour() { ImGui::PushStyleColor(ImGuiCol_TextDisabled, kHint); }
    ~HintColour() { ImGui::PopStyleColor(); }
    HintColour(const HintColour&) = delete;
    HintColour& operator=(const HintColour&) = delete;
};

// `line` cut at a word end so that it and an ellipsis fit in `width` (px, current font).
std::string withEllipsis(std::string_view line, float width) {
    // Three dots: the fonts' glyph ranges (Latin) have no U+2026.
    static constexpr std::string_view kEllipsis = "...";
    std::string_view kept = line;
    while (!kept.empty() && textWidth(std::string(kept) + std::string(kEllipsis)) > width) {
        const size_t space = kept.find_last_of(' ');
        kept = space == std::string_view::npos ? std::string_view{} : kept.substr(0, space);
    }
    while (!kept.empty() &&
           (kept.back() == ' ' || kept.back() == ',' || kept.back() == ':' || kept.back() == ';')) {
        kept.remove_suffix(1);
    }
    return std::string(kept) + std::string(kEllipsis);
}

// "52% / 80%", "312 / 500 particles", "1.20 / 2.00 L".
std::string progressText(const BannerInfo& info) {
    char buffer[96];
    switch (info.measure) {
    case GoalMeasure::Count:
        std::snprintf(buffer, sizeof buffer, "%.0f / %.0f particles", info.goalValue,
                      info.goalAmount);
        break;
    case GoalMeasure::Volume:
        std::snprintf(buffer, sizeof buffer, "%.2f / %.2f L", 1e3 * info.goalValue,
                      1e3 * info.goalAmount);
        break;
    case GoalMeasure::Fraction:
    default:
        std::snprintf(buffer, sizeof buffer, "%.0f%% / %.0f%%", 100.0 * info.goalValue,
                      100.0 * info.goalAmount);
        break;
    }
    return buffer;
}
} // namespace

std::span<const ControlHelp> controls() {
    return kControls;
}

std::vector<std::string_view> wrapWords(std::string_view text, float width,
                                        const std::function<float(std::string_view)>& measure) {
    std::vector<std::string_view> lines;
    size_t start = 0;
    while (start < text.size()) {
        // Spaces at a line's start belong to no line; a newline ends one.
        while (start < text.size() && text[start] == ' ') {
            ++start;
        }
        if (start >= text.size()) {
            break;
        }
        size_t end = start;    // end of the line so far (exclusive)
        size_t cursor = start; // start of the next word
        bool broken = false;
        while (cursor < text.size()) {
            size_t wordEnd = cursor;
            while (wordEnd < text.size() && text[wordEnd] != ' ' && text[wordEnd] != '\n') {
                ++wordEnd;
            }
            const std::string_view candidate = text.substr(start, wordEnd - start);
            if (end > start && measure(candidate) > width) {
                broken = true; // the word goes to the next line
                break;
            }
            end = wordEnd; // the first word of a line stays on it, even if it is too wide
            if (wordEnd >= text.size() || text[wordEnd] == '\n') {
                break;
            }
            cursor = wordEnd;
            while (cursor < text.size() && text[cursor] == ' ') {
                ++cursor;
            }
        }
        lines.push_back(text.substr(start, end - start));
        start = end;
        if (!broken && start < text.size() && text[start] == '\n') {
            ++start;
        }
    }
    return lines;
}

void drawHud(const HudInfo& info) {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + kEdge, viewport->WorkPos.y + kEdge));
    ImGui::SetNextWindowBgAlpha(kOverlayBackground);
    const HintColour hints;
    if (ImGui::Begin("##hud", nullptr, kOverlayFlags)) {
        ImGui::Text("%.0f fps", static_cast<double>(info.fps));
        ImGui::SameLine();
        ImGui::TextDisabled("|");
        ImGui::SameLine();
        ImGui::Text("%u particles", info.particles);
        ImGui::Text("sim %.1f ms/frame", static_cast<double>(info.simMsPerFrame));
        ImGui::SameLine();
        ImGui::TextDisabled("|");
        ImGui::SameLine();
        ImGui::Text("%u sub-steps", info.substeps);
        ImGui::TextDisabled("view");
        ImGui::SameLine();
        text(info.view);
        ImGui::SameLine();
        ImGui::TextDisabled("  material");
        ImGui::SameLine();
        text(info.material);
        if (info.zeroG) {
            ImGui::TextColored(kCyan, "zero-g");
        } else {
            ImGui::TextDisabled("gravity");
            ImGui::SameLine();
            text("on");
        }
        if (info.paused) {
            ImGui::TextColored(kAmber, "PAUSED");
            ImGui::SameLine();
            ImGui::TextDisabled("P resume, . step");
        }
        if (info.behind) {
            ImGui::TextColored(kAmber, "simulation behind: %.0f%% speed",
                               100.0 * std::max(info.speed, 0.0));
            ImGui::SameLine();
            ImGui::TextDisabled("(%llu dropped)",
                                static_cast<unsigned long long>(info.droppedSteps));
        }
        // The liquid under the cursor (fluid::sample) and the laser's hit (fluid::rayCast).
        if (!info.cursor.empty()) {
            ImGui::TextDisabled("cursor");
            ImGui::SameLine();
            text(info.cursor);
        }
        if (!info.laser.empty()) {
            ImGui::TextDisabled("laser");
            ImGui::SameLine();
            text(info.laser);
        }
        ImGui::TextDisabled("F1 help   Esc levels   Tab tuning");
        // Auto-resized: the size is the one measured in an earlier frame.
        g_hudRight =
            ImGui::GetWindowPos().x - viewport->WorkPos.x + ImGui::GetWindowWidth() + kEdge;
    }
    ImGui::End();
}

void drawLevelBanner(const BannerInfo& info, ImFont* big) {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float screenWidth = viewport->WorkSize.x;
    const float screenHeight = viewport->WorkSize.y;
    // Between the HUD and the window's right edge (the tuning panel's left edge while it is
    // open), centred on the window when that fits, else centred in the room; on a tiny window
    // over everything.
    const float roomLeft = std::max(g_hudRight, kEdge);
    const float roomRight = screenWidth - kEdge - (info.panelOpen ? kSideRoom : 0.0f);
    float width = std::min(kBannerMaxWidth, roomRight - roomLeft);
    float left = 0.5f * (screenWidth - width);
    if (left < roomLeft || left + width > roomRight) {
        left = roomLeft + 0.5f * (roomRight - roomLeft - width);
    }
    if (width < 240.0f) {
        width = std::max(std::min(kBannerMaxWidth, screenWidth - 2.0f * kEdge), 1.0f);
        left = 0.5f * (screenWidth - width);
    }
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + left, viewport->WorkPos.y + kEdge));
    ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, FLT_MAX));
    ImGui::SetNextWindowBgAlpha(kOverlayBackground);
    const HintColour hints;
    if (ImGui::Begin("##banner", nullptr, kOverlayFlags)) {
        const ImGuiStyle& style = ImGui::GetStyle();
        float used = 2.0f * style.WindowPadding.y;
        {
            const BigFont font(big, 1.0f);
            centredText(info.name);
            used += ImGui::GetTextLineHeightWithSpacing();
        }
        const bool goal = info.state != GoalState::None;
        if (goal) {
            // The progress bar (the clock in its label) and the spacing above it.
            used += ImGui::GetFrameHeightWithSpacing() + style.ItemSpacing.y;
        }
        if (!info.text.empty()) {
            // As many lines as the room above the level holds (at least one), broken at
            // spaces only; a cut text ends in an ellipsis.
            const float avail = ImGui::GetContentRegionAvail().x;
            const std::vector<std::string_view> lines = wrapWords(info.text, avail, textWidth);
            const float budget = kBannerRoom * screenHeight - kEdge;
            const size_t fit = static_cast<size_t>(
                std::max((budget - used) / ImGui::GetTextLineHeightWithSpacing(), 1.0f));
            const size_t shown = std::min(lines.size(), fit);
            for (size_t k = 0; k < shown; ++k) {
                std::string line(lines[k]);
                if (k + 1 == shown && shown < lines.size()) {
                    line = withEllipsis(lines[k], avail);
                }
                // One line is centred under the title; a paragraph is left-aligned.
                if (lines.size() == 1) {
                    centredText(line);
                } else {
                    text(line);
                }
            }
        }
        if (goal) {
            ImGui::Spacing();
            const double fraction = info.goalAmount > 0.0
                                        ? std::clamp(info.goalValue / info.goalAmount, 0.0, 1.0)
                                        : 0.0;
            const ImVec4 bar = info.state == GoalState::Won    ? kGreen
                               : info.state == GoalState::Lost ? kRed
                                                               : ImVec4(0.26f, 0.59f, 0.98f, 1.0f);
            // "312 / 500 particles    time left 41.2 s" (amber under 10 s), or the time played.
            std::string label = progressText(info);
            char clock[64];
            bool hurry = false;
            if (info.timeLimit > 0.0) {
                const double remaining = std::max(info.timeLimit - info.time, 0.0);
                std::snprintf(clock, sizeof clock, "    time left %.1f s", remaining);
                hurry = remaining < 10.0 && info.state == GoalState::Pending;
            } else {
                std::snprintf(clock, sizeof clock, "    time %.1f s", info.time);
            }
            label += clock;
            ImGui::PushStyleColor(ImGuiCol_PlotHistogram, bar);
            if (hurry) {
                ImGui::PushStyleColor(ImGuiCol_Text, kAmber);
            }
            ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(-1.0f, 0.0f), label.c_str());
            ImGui::PopStyleColor(hurry ? 2 : 1);
        }
    }
    ImGui::End();

    if (info.state != GoalState::Won && info.state != GoalState::Lost) {
        return;
    }
    const bool won = info.state == GoalState::Won;
    ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.7f);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(28.0f, 18.0f));
    if (ImGui::Begin("##outcome", nullptr, kOverlayFlags)) {
        {
            const BigFont font(big, 1.5f);
            ImGui::PushStyleColor(ImGuiCol_Text, won ? kGreen : kRed);
            centredText(won ? "Level complete!" : "Time's up");
            ImGui::PopStyleColor();
        }
        ImGui::Spacing();
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        centredText("R retry, N next level");
        ImGui::PopStyleColor();
    }
    ImGui::End();
    ImGui::PopStyleVar();
}

void drawHelp(bool* open, std::string_view levelName, std::string_view levelText) {
    if (open == nullptr || !*open) {
        return;
    }
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.92f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings;
    if (ImGui::Begin("Controls (F1)", open, flags)) {
        if (!levelName.empty()) {
            // The level's whole text, which the banner may have cut.
            ImGui::PushStyleColor(ImGuiCol_Text, kKey);
            text(levelName);
            ImGui::PopStyleColor();
            for (const std::string_view line : wrapWords(levelText, kHelpTextWidth, textWidth)) {
                text(line);
            }
            ImGui::Spacing();
            ImGui::Separator();
            ImGui::Spacing();
        }
        const ImGuiTableFlags tableFlags =
            ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_PadOuterX;
        if (ImGui::BeginTable("controls", 2, tableFlags)) {
            for (const ControlHelp& control : kControls) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::PushStyleColor(ImGuiCol_Text, kKey);
                text(control.keys);
                ImGui::PopStyleColor();
                ImGui::TableNextColumn();
                text(control.action);
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

int drawLevelMenu(std::span<const LevelEntry> levels, int current, bool* open) {
    if (open == nullptr || !*open) {
        return -1;
    }
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.94f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings;
    int chosen = -1;
    if (ImGui::Begin("Levels (Esc)", open, flags)) {
        // Column of the dimmed file stems: after the longest title.
        float titleWidth = 0.0f;
        for (const LevelEntry& level : levels) {
            const std::string& title = level.title.empty() ? level.stem : level.title;
            titleWidth = std::max(titleWidth, ImGui::CalcTextSize(title.c_str()).x);
        }
        const float numberWidth = ImGui::CalcTextSize("00 ").x;
        const float stemX = ImGui::GetCursorPosX() + numberWidth + titleWidth + 40.0f;
        for (std::size_t i = 0; i < levels.size(); ++i) {
            const LevelEntry& level = levels[i];
            const std::string& title = level.title.empty() ? level.stem : level.title;
            ImGui::PushID(static_cast<int>(i));
            const float rowX = ImGui::GetCursorPosX();
            const bool isCurrent = static_cast<int>(i) == current;
            // Width 0: the row spans the window, whose width the stems and buttons set.
            if (ImGui::Selectable("##level", isCurrent)) {
                chosen = static_cast<int>(i);
            }
            ImGui::SameLine(rowX);
            ImGui::TextDisabled("%zu", i + 1);
            ImGui::SameLine(rowX + numberWidth);
            if (isCurrent) {
                ImGui::TextColored(kKey, "%s", title.c_str());
            } else {
                text(title);
            }
            ImGui::SameLine(stemX);
            ImGui::TextDisabled("%s", level.stem.c_str());
            ImGui::PopID();
        }
        if (levels.empty()) {
            ImGui::TextDisabled("no level files found");
        }
        ImGui::Spacing();
        ImGui::Separator();
        ImGui::Spacing();
        if (ImGui::Button("Resume")) {
            *open = false;
        }
        ImGui::SameLine();
        if (ImGui::Button("Quit")) {
            chosen = -2;
        }
        ImGui::SameLine();
        ImGui::TextDisabled("  1-9 jump, N / B next / previous");
    }
    ImGui::End();
    if (chosen >= 0) {
        *open = false;
    }
    return chosen;
}

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

void drawToast(std::string_view message, float alpha) {
    if (message.empty()) {
        return;
    }
    const float a = std::isfinite(alpha) ? std::clamp(alpha, 0.0f, 1.0f) : 1.0f;
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + 0.5f * viewport->WorkSize.x,
                                   viewport->WorkPos.y + viewport->WorkSize.y - 40.0f),
                            ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::PushStyleVar(ImGuiStyleVar_Alpha, a);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(16.0f, 10.0f));
    if (ImGui::Begin("##toast", nullptr, kOverlayFlags)) {
        text(message);
    }
    ImGui::End();
    ImGui::PopStyleVar(2);
}

} // namespace fluid::demo
