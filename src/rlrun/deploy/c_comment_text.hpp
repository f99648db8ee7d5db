#pragma once
// Text that goes into a comment of generated C (`rlrun export --format c`: the model's
// metadata and Dict keys in policy.h). A model file is untrusted (docs/security.md), and in C
// a comment is not inert: `*/` ends it, a backslash before a newline splices the next line on
// (translation phase 2, so `*\` newline `/` is `*/` too), and `??/` is a backslash under
// -trigraphs (phase 1). What is left after the comment would be compiled into the user's
// program.
#include <string>
#include <string_view>

namespace rlrun {

// `text` for the inside of a /* */ comment: letters, digits, space and the punctuation of C's
// basic character set other than `\`, `*`, `?` and `%` pass; every other byte (those four,
// control characters, `$` `@` and backquote, bytes >= 0x80) becomes `%XX`, its value in hex:
// nothing in the result can end the comment, splice a line or form a trigraph, and the
// original bytes can be read back from it.
std::string c_comment_text(std::string_view text);

}  // namespace rlrun
