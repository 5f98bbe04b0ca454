#include "preprocess/classify/transfer_function.h"

#include <vtkColorTransferFunction.h>
#include <vtkPiecewiseFunction.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.h"
#include "core/printable_text.h"

namespace vr {
namespace {

// ParaView's ColorSpace names -> VTK's constants (ParaView leaves HSVWrap off).
int vtkColourSpace(const std::string& name) {
    if (name == "RGB") return VTK_CTF_RGB;
    if (name == "HSV") return VTK_CTF_HSV;
    if (name == "Lab") return VTK_CTF_LAB;
    if (name == "Lab/CIEDE2000") return VTK_CTF_LAB_CIEDE2000;
    if (name == "Diverging") return VTK_CTF_DIVERGING;
    if (name == "Step") return VTK_CTF_STEP;
    return -1;
}

vtkSmartPointer<vtkPiecewiseFunction> opacityFunction(const TransferFunction& tf) {
    auto f = vtkSmartPointer<vtkPiecewiseFunction>::New();
    f->ClampingOn();
    for (const auto& p : tf.opacity) f->AddPoint(p.x, p.opacity, p.midpoint, p.sharpness);
    return f;
}

vtkSmartPointer<vtkColorTransferFunction> colourFunction(const TransferFunction& tf) {
    auto f = vtkSmartPointer<vtkColorTransferFunction>::New();
    f->ClampingOn();
    f->HSVWrapOff();
    f->SetColorSpace(vtkColourSpace(tf.colourSpace));
    for (const auto& p : tf.colour) f->AddRGBPoint(p.x, p.r, p.g, p.b);
    return f;
}

bool inUnit(double v) { return v >= 0 && v <= 1; }

// A flat list of numbers whose length is a multiple of 4, as ParaView writes "Points" and "RGBPoints".
std::vector<double> quadruples(const nlohmann::json& preset, const char* key, const std::string& source) {
    const nlohmann::json& list = preset.at(key);
    if (!list.is_array()) throw fileError(source, std::string("\"") + key + "\" is not a list");
    if (list.size() % 4 != 0)
        throw fileError(source, std::string("\"") + key + "\" has " + std::to_string(list.size()) +
                                    " numbers, not a multiple of 4");
    std::vector<double> numbers;
    for (std::size_t i = 0; i < list.size(); ++i) {
        if (!list[i].is_number())
            throw fileError(source, std::string("\"") + key + "\"[" + std::to_string(i) + "] is not a number");
        numbers.push_back(list[i].get<double>());
    }
    return numbers;
}

}  // namespace

void TransferFunction::validate(const std::string& source) const {
    if (opacity.empty()) throw fileError(source, "the transfer function has no opacity points");
    for (std::size_t i = 0; i < opacity.size(); ++i) {
        const OpacityPoint& p = opacity[i];
        const std::string which = "opacity point " + std::to_string(i) + ": ";
        if (!std::isfinite(p.x) || !std::isfinite(p.opacity) || !std::isfinite(p.midpoint) ||
            !std::isfinite(p.sharpness))
            throw fileError(source, which + "not a finite number");
        if (!inUnit(p.opacity)) throw fileError(source, which + "opacity outside [0,1]");
        if (!inUnit(p.midpoint) || !inUnit(p.sharpness))
            throw fileError(source, which + "midpoint or sharpness outside [0,1]");
        if (i > 0 && !(p.x > opacity[i - 1].x)) throw fileError(source, which + "x not increasing (unsorted)");
    }
    for (std::size_t i = 0; i < colour.size(); ++i) {
        const ColourPoint& p = colour[i];
        const std::string which = "colour point " + std::to_string(i) + ": ";
        if (!std::isfinite(p.x) || !std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b))
            throw fileError(source, which + "not a finite number");
        if (!inUnit(p.r) || !inUnit(p.g) || !inUnit(p.b)) throw fileError(source, which + "colour outside [0,1]");
        if (i > 0 && !(p.x > colour[i - 1].x)) throw fileError(source, which + "x not increasing (unsorted)");
    }
    if (vtkColourSpace(colourSpace) < 0)
        throw fileError(source, "unsupported ColorSpace \"" + colourSpace +
                                    "\" (RGB, HSV, Lab, Lab/CIEDE2000, Diverging or Step)");
}

double TransferFunction::opacityAt(double f) const { return opacityFunction(*this)->GetValue(f); }

std::array<double, 3> TransferFunction::colourAt(double f) const {
    if (colour.empty()) return {1, 1, 1};
    std::array<double, 3> rgb;
    colourFunction(*this)->GetColor(f, rgb.data());
    return rgb;
}

double SampledTransferFunction::opacityAt(double f) const {
    std::size_t i;
    double w;
    locate(f, i, w);
    return w == 0 ? opacity[i] : opacity[i] + w * (opacity[i + 1] - opacity[i]);
}

std::array<float, 3> SampledTransferFunction::colourAt(double f) const {
    std::size_t i;
    double w;
    locate(f, i, w);
    if (w == 0) return colour[i];
    std::array<float, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = float(colour[i][k] + w * (double(colour[i + 1][k]) - colour[i][k]));
    return c;
}

SampledTransferFunction sampleTransferFunction(const TransferFunction& tf, double lo, double hi, std::size_t count) {
    SampledTransferFunction s;
    s.lo = lo;
    s.step = count > 1 ? (hi - lo) / double(count - 1) : 1.0;
    if (!(s.step > 0)) s.step = 1.0;  // hi == lo: one value, sampled `count` times
    s.opacity.resize(count);
    opacityFunction(tf)->GetTable(lo, hi, int(count), s.opacity.data());
    s.colour.assign(count, {1.f, 1.f, 1.f});
    if (!tf.colour.empty()) {
        std::vector<double> rgb(3 * count);
        colourFunction(tf)->GetTable(lo, hi, int(count), rgb.data());
        for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < 3; ++c)  // Lab and Diverging paths may leave the gamut by a rounding error
                s.colour[i][c] = float(std::clamp(rgb[3 * i + c], 0.0, 1.0));
    }
    return s;
}

TransferFunction parseTransferFunction(const std::string& jsonText, const std::string& sourceName) {
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(jsonText);
    } catch (const nlohmann::json::exception& e) {
        throw fileError(sourceName, std::string("malformed JSON: ") + printableText(e.what()));
    }
    if (doc.is_array()) {
        if (doc.empty()) throw fileError(sourceName, "the list of presets is empty");
        doc = doc[0];
    }
    if (!doc.is_object()) throw fileError(sourceName, "expected a ParaView preset (a JSON object or a list of them)");
    if (!doc.contains("Points")) throw fileError(sourceName, "no \"Points\" (opacity) in the preset");

    TransferFunction tf;
    tf.json = jsonText;
    if (doc.contains("Name") && doc["Name"].is_string()) tf.name = doc["Name"].get<std::string>();
    for (auto [key, text] : {std::pair{"Units", &tf.units}, std::pair{"Description", &tf.description}}) {
        if (!doc.contains(key)) continue;
        if (!doc[key].is_string()) throw fileError(sourceName, std::string("\"") + key + "\" is not a string");
        *text = doc[key].get<std::string>();
    }
    if (doc.contains("ColorSpace")) {
        if (!doc["ColorSpace"].is_string()) throw fileError(sourceName, "\"ColorSpace\" is not a string");
        tf.colourSpace = doc["ColorSpace"].get<std::string>();
    }
    const std::vector<double> points = quadruples(doc, "Points", sourceName);
    for (std::size_t i = 0; i < points.size(); i += 4)
        tf.opacity.push_back({points[i], points[i + 1], points[i + 2], points[i + 3]});
    if (doc.contains("RGBPoints")) {
        const std::vector<double> rgb = quadruples(doc, "RGBPoints", sourceName);
        for (std::size_t i = 0; i < rgb.size(); i += 4)
            tf.colour.push_back({rgb[i], rgb[i + 1], rgb[i + 2], rgb[i + 3]});
    }
    tf.validate(sourceName);
    return tf;
}

std::string shortNumber(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

std::string paraViewJson(const TransferFunction& tf) {
    nlohmann::json preset = {{"Name", tf.name}, {"ColorSpace", tf.colourSpace}};
    if (!tf.units.empty()) preset["Units"] = tf.units;
    if (!tf.description.empty()) preset["Description"] = tf.description;
    nlohmann::json& points = preset["Points"] = nlohmann::json::array();
    for (const auto& p : tf.opacity) points.insert(points.end(), {p.x, p.opacity, p.midpoint, p.sharpness});
    if (!tf.colour.empty()) {
        nlohmann::json& rgb = preset["RGBPoints"] = nlohmann::json::array();
        for (const auto& p : tf.colour) rgb.insert(rgb.end(), {p.x, p.r, p.g, p.b});
    }
    return nlohmann::json::array({preset}).dump(1);
}

TransferFunction loadTransferFunction(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fileError(path.string(), "cannot open the transfer function");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw fileError(path.string(), "cannot read the transfer function");
    return parseTransferFunction(text.str(), path.string());
}

}  // namespace vr
