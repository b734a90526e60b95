// Threading and grooving in a post: each form of each built-in, and every error.
#include <catch2/catch.hpp>

#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

TEST_CASE("placeholder thread", "[post][thread]") { CHECK(true); }
