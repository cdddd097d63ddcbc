// The items of an encoded BLOCK 1 where they stand: padding (0x55), then
// Item_ID and value back to back. For the receive path's look-ups in blocks
// it already knows to be exact, or encoded itself.
#pragma once

#include "codec/frame/Frame.h"
#include "codec/message/ItemTable.h"

#include <cstddef>

namespace rcm {

// Calls visit(info, offset) for each item, `offset` that of its Item_ID, up
// to an unknown Item_ID or an item the block's end cuts off; stops early when
// visit returns false.
template <typename Visit>
void forEachEncodedItem(const Block& block, Visit visit)
{
    std::size_t p = 0;
    while (p < kBlockSize && block[p] == kPad55)
        ++p;
    while (p < kBlockSize) {
        const ItemInfo* info = findItem(block[p]);
        if (!info || p + 1 + info->size > kBlockSize || !visit(*info, p))
            return;
        p += 1 + info->size;
    }
}

}  // namespace rcm
