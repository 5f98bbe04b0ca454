// Text from a file quoted in a message (core/printable_text.h): control bytes and bytes that are not UTF-8 escaped,
// UTF-8 kept, long text cut.
#include <gtest/gtest.h>

#include "core/printable_text.h"

namespace vr {
namespace {

TEST(CorePrintableText, EscapesControlAndBinaryBytesAndKeepsUtf8) {
    EXPECT_EQ(printableText("sizes: 10 3 2"), "sizes: 10 3 2");
    EXPECT_EQ(printableText(std::string("a\0b\x1b[2Jc\x7f", 9)), "a\\x00b\\x1B[2Jc\\x7F");
    EXPECT_EQ(printableText("Pr\xC3\xA4zentral \xE2\x86\x92 \xF0\x9F\xA7\xA0"), "Pr\xC3\xA4zentral \xE2\x86\x92 \xF0\x9F\xA7\xA0");
    // A lone continuation byte, a sequence cut short, an overlong lead and a lead beyond U+10FFFF.
    EXPECT_EQ(printableText("\x80x\xC3"), "\\x80x\\xC3");
    EXPECT_EQ(printableText("\xC0\xAF\xF5\x80\x80\x80"), "\\xC0\\xAF\\xF5\\x80\\x80\\x80");
    EXPECT_EQ(printableText("\xE2\x86z"), "\\xE2\\x86z");
}

TEST(CorePrintableText, LongTextIsCut) {
    EXPECT_EQ(printableText(std::string(10, 'x'), 4), "xxxx...");
    EXPECT_EQ(printableText(std::string(4, 'x'), 4), "xxxx");
    EXPECT_EQ(printableText(std::string(1 << 20, 'y')).size(), 203u);  // 200 bytes and "..."
}

}  // namespace
}  // namespace vr
