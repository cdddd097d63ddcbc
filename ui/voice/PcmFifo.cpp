#include "ui/voice/PcmFifo.h"

#include <algorithm>

void PcmFifo::push(std::span<const std::int16_t> pcm)
{
    const std::lock_guard lock(m_mutex);
    m_samples.insert(m_samples.end(), pcm.begin(), pcm.end());
    if (m_samples.size() > m_capacity) {
        const std::size_t drop = m_samples.size() - m_capacity;
        m_samples.erase(m_samples.begin(), m_samples.begin() + std::ptrdiff_t(drop));
        m_dropped += drop;
    }
}

std::size_t PcmFifo::pull(std::span<std::int16_t> out)
{
    const std::lock_guard lock(m_mutex);
    const std::size_t n = std::min(out.size(), m_samples.size());
    std::copy_n(m_samples.begin(), n, out.begin());
    m_samples.erase(m_samples.begin(), m_samples.begin() + std::ptrdiff_t(n));
    std::fill(out.begin() + std::ptrdiff_t(n), out.end(), std::int16_t{0});
    return n;
}

std::size_t PcmFifo::size() const
{
    const std::lock_guard lock(m_mutex);
    return m_samples.size();
}

void PcmFifo::clear()
{
    const std::lock_guard lock(m_mutex);
    m_samples.clear();
}

std::uint64_t PcmFifo::samplesDropped() const
{
    const std::lock_guard lock(m_mutex);
    return m_dropped;
}
