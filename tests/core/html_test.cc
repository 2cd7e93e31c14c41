#include "bcot/core/html.h"

#include <gtest/gtest.h>

namespace bcot {
namespace {

TEST(HtmlEscapeTest, EscapesMarkupAndBothQuotes) {
  EXPECT_EQ(HtmlEscape("a<b> & \"c\" 'd'"), "a&lt;b&gt; &amp; &quot;c&quot; &#39;d&#39;");
  EXPECT_EQ(HtmlEscape("plain/path_01"), "plain/path_01");
  EXPECT_EQ(HtmlEscape(""), "");
}

}  // namespace
}  // namespace bcot
