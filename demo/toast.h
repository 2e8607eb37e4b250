// fluid-demo — toasts: short messages at the bottom centre that go after a few seconds.
#pragma once

#include <chrono>
#include <string>
#include <string_view>

namespace fluid::demo {

/// Draws a short message bottom-centre (errors such as "world full"), at opacity `alpha`
/// (unit: 1; range [0, 1]) so the caller can fade it out. Takes no input. Thread rule: between
/// `ImGuiBridge::newFrame` and `render`, on the GL thread.
void drawToast(std::string_view message, float alpha = 1.0f);

/// The game's one toast: the last message shown, for 4 s. Main thread.
class Toast {
public:
    /// Shows `message` from now on, instead of any earlier one.
    void show(std::string message);
    /// Draws the message while it is shown (`drawToast`); nothing after its 4 s.
    void draw() const;

private:
    std::string m_message;
    std::chrono::steady_clock::time_point m_until{};
};

} // namespace fluid::demo
