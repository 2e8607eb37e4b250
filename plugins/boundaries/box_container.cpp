// fluid — built-in boundary plugin: axis-aligned box container.
#include <fluid/error.h>
#include <fluid/plugins/box_container.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace fluid {

BoxContainer::BoxContainer(float minX, float minY, float maxX, float maxY) : BoxContainer() {
    setParam("minX", minX);
    setParam("minY", minY);
    setParam("maxX", maxX);
    setParam("maxY", maxY);
    checkParams();
}

void BoxContainer::onParamChanged(std::size_t /*index*/) {
    m_builtSpacing = 0.0f; // lay the samples again at the next prepare
}

void BoxContainer::checkParams() const {
    const double x0 = value(kMinX), y0 = value(kMinY), x1 = value(kMaxX), y1 = value(kMaxY);
    if (!(x0 < x1 && y0 < y1)) {
        std::ostringstream s;
        s << "plugin 'boundary.box': the inner rectangle [" << x0 << ", " << x1 << "] x [" << y0
          << ", " << y1 << "] is empty; expected minX < maxX and minY < maxY";
        throw Error(s.str(), ErrorCode::BadArgument);
    }
}

void BoxContainer::prepare(const StepContext& context) {
    checkParams(); // parameters set one by one after the plugin joined a world
    const double x0 = value(kMinX), y0 = value(kMinY), x1 = value(kMaxX), y1 = value(kMaxY);
    if (m_builtSpacing == context.sampleSpacing && m_builtSupport == context.supportRadius) {
        return;
    }
    const double s = context.sampleSpacing;
    // Enough layers to fill a whole support radius behind the surface.
    const int layers = static_cast<int>(std::ceil(context.supportRadius / s));
    const bool openTop = value(kOpenTop) >= 0.5;
    // Columns: inside ones aligned to the left wall, then `layers` behind each side wall, the
    // first half a spacing behind the surface (where the fluid lattice's next row would be).
    std::vector<double> xs, ys;
    for (int l = layers - 1; l >= 0; --l) {
        xs.push_back(x0 - (l + 0.5) * s);
    }
    for (double x = x0 + 0.5 * s; x < x1; x += s) {
        xs.push_back(x);
    }
    for (int l = 0; l < layers; ++l) {
        xs.push_back(x1 + (l + 0.5) * s);
    }
    for (int l = layers - 1; l >= 0; --l) {
        ys.push_back(y0 - (l + 0.5) * s);
    }
    for (double y = y0 + 0.5 * s; y < y1; y += s) {
        ys.push_back(y);
    }
    if (!openTop) {
        for (int l = 0; l < layers; ++l) {
            ys.push_back(y1 + (l + 0.5) * s);
        }
    }
    m_samples.clear();
    for (double y : ys) {
        for (double x : xs) {
            if (x < x0 || x > x1 || y < y0 || y > y1) {
                m_samples.add(static_cast<float>(x), static_cast<float>(y));
            }
        }
    }
    m_builtSpacing = context.sampleSpacing;
    m_builtSupport = context.supportRadius;
}

bool BoxContainer::contains(glm::vec2 point) const {
    const double x = point.x, y = point.y;
    const bool openTop = value(kOpenTop) >= 0.5;
    return x < value(kMinX) || x > value(kMaxX) || y < value(kMinY) ||
           (!openTop && y > value(kMaxY));
}

void BoxContainer::project(const ProjectContext& context, uint32_t begin, uint32_t end) {
    const auto x0 = static_cast<float>(value(kMinX));
    const auto y0 = static_cast<float>(value(kMinY));
    const auto x1 = static_cast<float>(value(kMaxX));
    const auto y1 = static_cast<float>(value(kMaxY));
    const bool openTop = value(kOpenTop) >= 0.5;
    for (uint32_t i = begin; i < end; ++i) {
        float& x = context.px[i];
        float& y = context.py[i];
        if (openTop && y > y1) {
            continue; // above an open tank: no wall here
        }
        // Back to the surface, and no velocity into the wall.
        if (x < x0) {
            x = x0;
            context.vx[i] = std::max(context.vx[i], 0.0f);
        } else if (x > x1) {
            x = x1;
            context.vx[i] = std::min(context.vx[i], 0.0f);
        }
        if (y < y0) {
            y = y0;
            context.vy[i] = std::max(context.vy[i], 0.0f);
        } else if (!openTop && y > y1) {
            y = y1;
            context.vy[i] = std::min(context.vy[i], 0.0f);
        }
    }
}

} // namespace fluid
