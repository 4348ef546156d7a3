// The error of the comparison: something it cannot do (an absurd option, a scheme that cannot be
// built, a metric that cannot measure); the message says what and why.
#pragma once

#include <stdexcept>

namespace ellicast::compare {

class CompareError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace ellicast::compare
