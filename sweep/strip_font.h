// The labels of the image strips: text drawn by FreeType in DejaVu Sans, where that font is installed.
#pragma once
#include <string>
#include <vector>

struct FT_LibraryRec_;  // FreeType's, kept out of the users of this header
struct FT_FaceRec_;

namespace vr {

class StripFont {
public:
    // Looks for DejaVuSans.ttf under the system's font folders; without it every draw() draws nothing.
    explicit StripFont(int pixelSize);
    ~StripFont();
    StripFont(const StripFont&) = delete;
    StripFont& operator=(const StripFont&) = delete;

    bool found() const { return face_ != nullptr; }
    // White text from x with its baseline at `baseline`, blended by coverage over the RGB bytes (3 a pixel, from the
    // top row) of a width x height image; what falls outside is cut off.
    void draw(std::vector<unsigned char>& rgb, int width, int height, int x, int baseline,
              const std::string& text) const;

private:
    FT_LibraryRec_* library_ = nullptr;
    FT_FaceRec_* face_ = nullptr;
};

}  // namespace vr
